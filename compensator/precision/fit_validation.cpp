#include "compensator/precision/fit_validation.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <functional>

#include "compensator/support/error.hpp"

namespace roprec {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

/// The observation's residual directions as rows (2 for a hole, 3 for a point), base frame.
MatrixXd rowsOf(const IdentificationHole& h) {
  const Mat3 R = h.T_W_hole.linear();
  return R.leftCols(observationRows(h)).transpose();
}

/// A candidate effect: its 3×p displacement at observation i (of n) at position p_W.
using EffectColumns = std::function<MatrixXd(size_t i, size_t n, const Vec3& p_W)>;

double order(size_t i, size_t n) {
  return n > 1 ? static_cast<double>(i) / static_cast<double>(n - 1) : 0.0;
}

/// Least squares of the weighted residual w on the weighted effect columns: β and the share of
/// ‖w‖² it removes.
std::pair<VectorXd, double> fitEffect(const IdentificationResult& r,
                                      const std::vector<IdentificationHole>& holes,
                                      const EffectColumns& effect) {
  const size_t n = holes.size();
  std::vector<MatrixXd> blocks;
  std::vector<VectorXd> w;
  Eigen::Index rows = 0;
  for (size_t i = 0; i < n; ++i) {
    const MatrixXd B = rowsOf(holes[i]);
    // where the observation is: a drilled hole's nominal point, a tracker point's measured one
    // (its T_W_hole carries only the residual axes)
    const Vec3 p_W = holes[i].point ? holes[i].p_W_measured : holes[i].T_W_hole.translation();
    const MatrixXd E = B * effect(i, n, p_W) / holes[i].sigma;
    const int o = orientationRows(holes[i]);
    // a measured orientation: its rows as the fit has them (the candidate effects move positions)
    MatrixXd block = MatrixXd::Zero(E.rows() + o, E.cols());
    block.topRows(E.rows()) = E;
    VectorXd wi(E.rows() + o);
    wi.head(E.rows()) = r.residuals[i] / holes[i].sigma;
    if (o > 0)
      wi.tail(o) = i < r.rotation_residuals.size()
                       ? VectorXd(r.rotation_residuals[i] / holes[i].sigma_rotation)
                       : VectorXd::Zero(o);
    blocks.push_back(block);
    w.push_back(wi);
    rows += block.rows();
  }
  MatrixXd A(rows, blocks.front().cols());
  VectorXd b(rows);
  Eigen::Index at = 0;
  for (size_t i = 0; i < n; ++i) {
    A.middleRows(at, blocks[i].rows()) = blocks[i];
    b.segment(at, w[i].size()) = w[i];
    at += blocks[i].rows();
  }
  // what the fit could have absorbed is not the effect's: only the part of each candidate column
  // outside the span of the fit's Jacobian can explain the residual
  if (r.jacobian.rows() == rows && r.jacobian.cols() > 0) {
    const Eigen::ColPivHouseholderQR<MatrixXd> qr(r.jacobian);
    A -= r.jacobian * qr.solve(A);
  }
  const Eigen::ColPivHouseholderQR<MatrixXd> qr(A);
  if (qr.rank() == 0) return {VectorXd::Zero(A.cols()), 0.0};  // the fit absorbs it all
  const VectorXd beta = qr.solve(b);
  const double total = b.squaredNorm();
  const double share = total > 0 ? 1.0 - (b - A * beta).squaredNorm() / total : 0.0;
  return {beta, std::clamp(share, 0.0, 1.0)};
}

std::string um(double m) { return numberText(m * 1e6, 3); }

std::vector<UnmodelledEffect> candidateEffects(const IdentificationResult& r,
                                               const std::vector<IdentificationHole>& holes) {
  std::vector<UnmodelledEffect> out;
  {
    const auto [b, share] =
        fitEffect(r, holes, [](size_t, size_t, const Vec3& p) { return MatrixXd(p); });
    out.push_back({"length scale", numberText(b[0] * 1e3, 3) + " mm/m", share});
  }
  {
    const auto [b, share] = fitEffect(r, holes, [](size_t i, size_t n, const Vec3&) {
      return MatrixXd(Mat3::Identity() * order(i, n));
    });
    out.push_back(
        {"drift with time", "(" + um(b[0]) + ", " + um(b[1]) + ", " + um(b[2]) + ") µm", share});
  }
  {
    const auto [b, share] = fitEffect(
        r, holes, [](size_t i, size_t n, const Vec3& p) { return MatrixXd(p * order(i, n)); });
    out.push_back({"scale drifting with time", numberText(b[0] * 1e3, 3) + " mm/m", share});
  }
  return out;
}

double rmsOf(const std::vector<double>& v) {
  double s = 0;
  for (const double x : v) s += x * x;
  return v.empty() ? 0.0 : std::sqrt(s / static_cast<double>(v.size()));
}

void finish(HeldOutValidation& v) {
  v.rms_calibrated = rmsOf(v.calibrated);
  v.rms_original = rmsOf(v.original);
  v.better = v.rms_calibrated < v.rms_original;
}

IdentificationOptions originalCard(const IdentificationOptions& o) {
  IdentificationOptions b = o;
  b.identify = IdentifySet::kNone;
  return b;
}

}  // namespace

double chiSquareQuantile(int dof, double p) {
  if (dof < 1) return 0.0;
  // standard normal quantile (Acklam's rational approximation, |error| < 1.2e-9 relative)
  const double q = p - 0.5;
  double z = 0;
  if (std::abs(q) <= 0.425) {
    const double r = 0.180625 - q * q;
    z = q *
        (((((((2509.0809287301226727 * r + 33430.575583588128105) * r + 67265.770927008700853) * r +
             45921.953931549871457) *
                r +
            13731.693765509461125) *
               r +
           1971.5909503065514427) *
              r +
          133.14166789178437745) *
             r +
         3.387132872796366608) /
        (((((((5226.495278852545925 * r + 28729.085735721942674) * r + 39307.89580009271061) * r +
             21213.794301586595867) *
                r +
            5394.1960214247511077) *
               r +
           687.1870074920579083) *
              r +
          42.313330701600911252) *
             r +
         1.0);
  } else {
    double r = q < 0 ? p : 1.0 - p;
    r = std::sqrt(-std::log(r));
    if (r <= 5.0) {
      r -= 1.6;
      z = (((((((7.7454501427834140764e-4 * r + 0.0227238449892691845833) * r +
                0.24178072517745061177) *
                   r +
               1.27045825245236838258) *
                  r +
              3.64784832476320460504) *
                 r +
             5.7694972214606914055) *
                r +
            4.6303378461565452959) *
               r +
           1.42343711074968357734) /
          (((((((1.05075007164441684324e-9 * r + 5.475938084995344946e-4) * r +
                0.0151986665636164571966) *
                   r +
               0.14810397642748007459) *
                  r +
              0.68976733498510000455) *
                 r +
             1.6763848301838038494) *
                r +
            2.05319162663775882187) *
               r +
           1.0);
    } else {
      r -= 5.0;
      z = (((((((2.01033439929228813265e-7 * r + 2.71155556874348757815e-5) * r +
                0.0012426609473880784386) *
                   r +
               0.026532189526576123093) *
                  r +
              0.29656057182850489123) *
                 r +
             1.7848265399172913358) *
                r +
            5.4637849111641143699) *
               r +
           6.6579046435011037772) /
          (((((((2.04426310338993978564e-15 * r + 1.4215117583164458887e-7) * r +
                1.8463183175100546818e-5) *
                   r +
               7.868691311456132591e-4) *
                  r +
              0.0148753612908506148525) *
                 r +
             0.13692988092273580531) *
                r +
            0.59983220655588793769) *
               r +
           1.0);
    }
    if (q < 0) z = -z;
  }
  const double k = static_cast<double>(dof);
  const double a = 2.0 / (9.0 * k);
  const double c = 1.0 - a + z * std::sqrt(a);
  return k * c * c * c;
}

FitCheck checkFit(const IdentificationResult& r, const std::vector<IdentificationHole>& holes,
                  double rms_limit) {
  FitCheck f;
  f.chi2 = r.chi2;
  f.dof = std::max(1, r.dof);
  f.rms_normalized = std::sqrt(f.chi2 / f.dof);
  f.chi2_999 = chiSquareQuantile(f.dof, 0.999);
  f.rms_limit = rms_limit;
  f.consistent = f.rms_normalized <= rms_limit;
  if (holes.size() != r.residuals.size() || holes.empty()) return f;
  const std::vector<UnmodelledEffect> effects = candidateEffects(r, holes);
  f.best = *std::max_element(effects.begin(), effects.end(),
                             [](const auto& a, const auto& b) { return a.share < b.share; });
  if (f.consistent) return f;
  f.explanation = "the fit residual is " + numberText(f.rms_normalized, 3) +
                  " times the measurement σ (χ² " + numberText(f.chi2, 4) + " for " +
                  std::to_string(f.dof) + " degrees of freedom, 99.9 % quantile " +
                  numberText(f.chi2_999, 4) + "): ";
  if (f.best.share >= 0.5) {
    f.explanation += "the model cannot explain a " + f.best.name + " of " + f.best.value + " (" +
                     numberText(100 * f.best.share, 3) +
                     " % of χ²; thermal growth, a drifting fixture or tracker?)";
  } else {
    f.explanation +=
        "the model cannot explain scatter without the structure of a length scale or a drift "
        "(largest: " +
        f.best.name + ", " + numberText(100 * f.best.share, 3) +
        " % of χ²): backlash, a loose fixture or part, or a measurement σ set too small";
  }
  return f;
}

HeldOutValidation crossValidate(const PredictionModel& m,
                                const std::vector<IdentificationHole>& holes,
                                const IdentificationOptions& o, int folds) {
  if (folds < 2) throw InputError("", 0, "cross-validation needs at least 2 folds");
  if (static_cast<int>(holes.size()) < folds)
    throw InputError("", 0,
                     "cross-validation: " + std::to_string(holes.size()) + " observations for " +
                         std::to_string(folds) + " folds");
  HeldOutValidation v;
  v.folds = folds;
  v.calibrated.assign(holes.size(), 0.0);
  v.original.assign(holes.size(), 0.0);
  const IdentificationOptions base = originalCard(o);
  for (int f = 0; f < folds; ++f) {
    std::vector<IdentificationHole> fit;
    std::vector<IdentificationHole> out;
    std::vector<size_t> index;
    for (size_t i = 0; i < holes.size(); ++i) {
      if (static_cast<int>(i % static_cast<size_t>(folds)) == f) {
        out.push_back(holes[i]);
        index.push_back(i);
      } else {
        fit.push_back(holes[i]);
      }
    }
    const auto cal = residualsAt(m, identifyStiffness(m, fit, o), out, o);
    const auto org = residualsAt(m, identifyStiffness(m, fit, base), out, base);
    for (size_t k = 0; k < index.size(); ++k) {
      v.calibrated[index[k]] = cal[k].norm();
      v.original[index[k]] = org[k].norm();
    }
  }
  finish(v);
  return v;
}

double modelErrorFloor(const std::vector<double>& residual_norms,
                       const std::vector<IdentificationHole>& holes, double inflation) {
  double rr = 0.0;
  double noise = 0.0;
  double rows = 0.0;
  for (size_t i = 0; i < holes.size() && i < residual_norms.size(); ++i) {
    const double n = observationRows(holes[i]);
    rr += residual_norms[i] * residual_norms[i];
    noise += n * holes[i].sigma * holes[i].sigma;
    rows += n;
  }
  if (!(rows > 0)) return 0.0;
  return std::sqrt(std::max(0.0, (inflation * rr - noise) / rows));
}

HeldOutValidation validateOn(const PredictionModel& m, const IdentificationResult& r,
                             const std::vector<IdentificationHole>& fit,
                             const std::vector<IdentificationHole>& held_out,
                             const IdentificationOptions& o) {
  HeldOutValidation v;
  const IdentificationOptions base = originalCard(o);
  for (const Eigen::VectorXd& e : residualsAt(m, r, held_out, o)) v.calibrated.push_back(e.norm());
  for (const Eigen::VectorXd& e : residualsAt(m, identifyStiffness(m, fit, base), held_out, base))
    v.original.push_back(e.norm());
  finish(v);
  return v;
}

}  // namespace roprec
