#include "compensator/robot/counterbalance.hpp"

#include <cmath>
#include <limits>

namespace roprec {

double balancerLength(const Counterbalance& cb, double q) {
  const double psi = cb.psi0 + cb.sign * q;
  return std::sqrt(cb.r * cb.r + cb.d * cb.d - 2.0 * cb.r * cb.d * std::cos(psi));
}

double balancerStroke(const Counterbalance& cb, double length) {
  return cb.action == Counterbalance::Action::kPush ? cb.length_ref - length
                                                    : length - cb.length_ref;
}

namespace {
/// f(σ) ≥ 0: the balancer's load magnitude at stroke σ.
double loadMagnitude(const Counterbalance& cb, double stroke) {
  if (cb.law == Counterbalance::Law::kSpring) return cb.force_ref + cb.stiffness * stroke;
  const double v = cb.volume_ref - cb.area * stroke;
  if (!(v > 0)) return std::numeric_limits<double>::infinity();
  return cb.pressure_ref * cb.area * std::pow(cb.volume_ref / v, cb.polytropic);
}
}  // namespace

double balancerForce(const Counterbalance& cb, double length) {
  const double f = loadMagnitude(cb, balancerStroke(cb, length));
  return cb.action == Counterbalance::Action::kPush ? f : -f;
}

double balancerTorque(const Counterbalance& cb, double q) {
  if (!cb.present()) return 0.0;
  const double psi = cb.psi0 + cb.sign * q;
  const double l = balancerLength(cb, q);
  return cb.sign * balancerForce(cb, l) * cb.r * cb.d * std::sin(psi) / l;
}

double balancerEnergy(const Counterbalance& cb, double q) {
  if (!cb.present()) return 0.0;
  const double s = balancerStroke(cb, balancerLength(cb, q));
  if (cb.law == Counterbalance::Law::kSpring) return cb.force_ref * s + 0.5 * cb.stiffness * s * s;
  // ∫₀^σ p_ref A (V₀/(V₀ − Aσ'))ⁿ dσ' = p_ref V₀ⁿ ∫_{V}^{V₀} V'^(−n) dV'
  const double v0 = cb.volume_ref;
  const double v = v0 - cb.area * s;
  if (!(v > 0)) return std::numeric_limits<double>::infinity();
  const double n = cb.polytropic;
  if (std::abs(n - 1.0) < 1e-12) return cb.pressure_ref * v0 * std::log(v0 / v);
  return cb.pressure_ref * std::pow(v0, n) * (std::pow(v, 1.0 - n) - std::pow(v0, 1.0 - n)) /
         (n - 1.0);
}

std::string balancerProblem(const Counterbalance& cb, double lower, double upper) {
  if (!(cb.r > 0) || !(cb.d > 0)) return "r_mm and d_mm must be > 0";
  if (cb.sign != 1.0 && cb.sign != -1.0) return "sign must be 1 or -1";
  if (!(cb.length_ref > 0)) return "length_ref_mm must be > 0";
  if (cb.law == Counterbalance::Law::kSpring) {
    if (cb.force_ref < 0 || cb.stiffness < 0) return "preload_N and rate_N_per_mm must be >= 0";
  } else if (!(cb.pressure_ref > 0) || !(cb.area > 0) || !(cb.volume_ref > 0) ||
             !(cb.polytropic >= 1.0 && cb.polytropic <= 1.67)) {
    return "pressure_ref_MPa, piston_area_mm2, gas_volume_l must be > 0 and polytropic_n in "
           "[1, 1.67]";
  }
  const int n = 400;
  for (int i = 0; i <= n; ++i) {
    const double q = lower + (upper - lower) * i / n;
    const double l = balancerLength(cb, q);
    if (!(l > 1e-6)) return "the balancer length vanishes within the joint range";
    if (!std::isfinite(balancerForce(cb, l)) || loadMagnitude(cb, balancerStroke(cb, l)) < 0)
      return "the balancer force is not physical within the joint range (gas volume exhausted "
             "or spring unloaded below zero)";
  }
  return "";
}

}  // namespace roprec
