#pragma once
// Dead reckoning of an ideal IMU stream with RK4, independent of the generator: the state
// (R_world_imu, v_world, p_world) obeys dR/dt = R [w]x, dv/dt = R a + g, dp/dt = v. Steps span
// two samples (k, k+1, k+2), so the RK4 midpoint uses the real middle sample and no
// interpolation enters; the quaternion is renormalised after each step.
#include <vector>

#include "sensors/imu.h"

namespace inet::test {

struct InertialState {
  Quat q = Quat::Identity();
  Vec3 v = Vec3::Zero(), p = Vec3::Zero();
};

inline InertialState integrateRk4(const std::vector<ImuSample>& s, size_t first, size_t last,
                                  InertialState x, const Vec3& g) {
  struct Deriv {
    Quat dq;
    Vec3 dv, dp;
  };
  auto f = [&](const InertialState& st, const ImuSample& m) {
    Deriv d;
    const Quat w(0, 0.5 * m.gyro.x(), 0.5 * m.gyro.y(), 0.5 * m.gyro.z());
    d.dq = st.q * w;
    d.dv = st.q.normalized() * m.accel + g;
    d.dp = st.v;
    return d;
  };
  auto step = [](const InertialState& st, const Deriv& d, double h) {
    InertialState o;
    o.q.coeffs() = st.q.coeffs() + h * d.dq.coeffs();
    o.v = st.v + h * d.dv;
    o.p = st.p + h * d.dp;
    return o;
  };
  for (size_t k = first; k + 2 <= last; k += 2) {
    const double h = static_cast<double>(s[k + 2].t_ns - s[k].t_ns) * 1e-9;
    const Deriv k1 = f(x, s[k]);
    const Deriv k2 = f(step(x, k1, h / 2), s[k + 1]);
    const Deriv k3 = f(step(x, k2, h / 2), s[k + 1]);
    const Deriv k4 = f(step(x, k3, h), s[k + 2]);
    x.q.coeffs() += h / 6 * (k1.dq.coeffs() + 2 * k2.dq.coeffs() + 2 * k3.dq.coeffs() +
                             k4.dq.coeffs());
    x.q.normalize();
    x.v += h / 6 * (k1.dv + 2 * k2.dv + 2 * k3.dv + k4.dv);
    x.p += h / 6 * (k1.dp + 2 * k2.dp + 2 * k3.dp + k4.dp);
  }
  return x;
}

}  // namespace inet::test
