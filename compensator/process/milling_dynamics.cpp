#include "compensator/process/milling_dynamics.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "compensator/robot/inverse_dynamics.hpp"

namespace roprec {

namespace {

constexpr double kLockedStiffness = 1e15;  // N m/rad: a joint this stiff is rigid (locked)

/// Milling frame of a TCP orientation: v_mill = S R_W_tcpᵀ v_base, S = diag(1, −1, −1).
Mat3 millingFromBase(const Mat3& R_W_tcp) {
  Mat3 S = Mat3::Identity();
  S(1, 1) = -1;
  S(2, 2) = -1;
  return S * R_W_tcp.transpose();
}

/// The flexible joints (k_eff below kLockedStiffness), in joint order.
std::vector<int> flexibleJoints(const nc::Vec6& k_eff) {
  std::vector<int> idx;
  for (int j = 0; j < 6; ++j)
    if (k_eff[j] < kLockedStiffness) idx.push_back(j);
  return idx;
}

}  // namespace

double VibrationMode::tcpStiffness() const {
  const double u2 = tcp.squaredNorm();
  return u2 > 0 ? omega * omega / u2 : std::numeric_limits<double>::infinity();
}

Mat3c receptance(const ModalModel& model, double omega) {
  Mat3c H = Mat3c::Zero();
  for (const VibrationMode& m : model.modes) {
    const std::complex<double> den(m.omega * m.omega - omega * omega, 2 * m.zeta * m.omega * omega);
    H += (m.tcp * m.tcp.transpose()).cast<std::complex<double>>() / den;
  }
  return H;
}

Mat3 toolStaticCompliance(const ToolModeSpec& tool) {
  return Vec3(1.0 / tool.stiffness, 1.0 / tool.stiffness, 0.0).asDiagonal();
}

void addToolMode(ModalModel& model, const ToolModeSpec& tool) {
  const double w = 2 * kPi * tool.frequency_hz;
  const double mass = tool.stiffness / (w * w);
  for (int axis = 0; axis < 2; ++axis) {
    VibrationMode m;
    m.omega = w;
    m.zeta = tool.damping_ratio;
    m.tcp = Vec3::Unit(axis) / std::sqrt(mass);
    m.robot = false;
    model.modes.push_back(m);
  }
}

ModalModel robotModes(const nc::Model& model, const nc::JointCompliance& compliance,
                      const nc::Vec6& theta, double damping_ratio) {
  nc::Data data(model);
  if (!nc::forwardKinematics(model, data, theta).converged)
    throw std::runtime_error("robot modes: the position problem did not converge at the pose");
  const nc::Mat6 M = nc::jointSpaceInertia(model, data);
  const nc::Mat6 J = nc::tcpJacobian(model, data);
  const Mat3 T = millingFromBase(data.T_W_tcp.linear());
  const nc::Vec6 k = compliance.effective();
  const std::vector<int> idx = flexibleJoints(k);
  const auto n = static_cast<Eigen::Index>(idx.size());
  ModalModel out;
  if (n == 0) return out;
  Eigen::MatrixXd Mr(n, n);
  Eigen::MatrixXd Kr = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index a = 0; a < n; ++a) {
    Kr(a, a) = k[idx[static_cast<size_t>(a)]];
    for (Eigen::Index b = 0; b < n; ++b)
      Mr(a, b) = M(idx[static_cast<size_t>(a)], idx[static_cast<size_t>(b)]);
  }
  // the generalized problem K φ = ω² M φ (M SPD): eigenvectors come M-normalised
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Kr, Mr);
  if (es.info() != Eigen::Success)
    throw std::runtime_error("robot modes: the mass matrix is not positive definite at the pose");
  for (Eigen::Index r = 0; r < n; ++r) {
    VibrationMode m;
    m.omega = std::sqrt(std::max(0.0, es.eigenvalues()[r]));
    m.zeta = damping_ratio;
    nc::Vec6 phi = nc::Vec6::Zero();
    for (Eigen::Index a = 0; a < n; ++a) phi[idx[static_cast<size_t>(a)]] = es.eigenvectors()(a, r);
    m.tcp = T * (J.topRows<3>() * phi);
    Eigen::Index big = 0;
    phi.cwiseAbs().maxCoeff(&big);
    m.joints = phi / phi[big];  // largest entry +1: a sign-stable shape
    out.modes.push_back(m);
  }
  return out;
}

std::vector<Vec3> periodicResponse(const ModalModel& model, const std::vector<Vec3>& force,
                                   double spindle_rpm) {
  const size_t N = force.size();
  std::vector<Vec3> x(N, Vec3::Zero());
  if (N < 3) return x;
  const double Omega = 2 * kPi * spindle_rpm / 60.0;
  const size_t kmax = (N - 1) / 2;
  std::vector<std::complex<double>> rot(N);  // e^{−i 2π n/N}
  for (size_t n = 0; n < N; ++n)
    rot[n] = std::polar(1.0, -2 * kPi * static_cast<double>(n) / static_cast<double>(N));
  for (size_t k = 1; k <= kmax; ++k) {
    Eigen::Vector3cd Fk = Eigen::Vector3cd::Zero();
    for (size_t n = 0; n < N; ++n) Fk += force[n].cast<std::complex<double>>() * rot[(k * n) % N];
    Fk /= static_cast<double>(N);
    if (Fk.norm() == 0) continue;
    const Eigen::Vector3cd Xk = receptance(model, static_cast<double>(k) * Omega) * Fk;
    for (size_t n = 0; n < N; ++n) x[n] += 2.0 * (Xk * std::conj(rot[(k * n) % N])).real();
  }
  return x;
}

}  // namespace roprec
