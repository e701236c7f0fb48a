#include "render/fresnel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>

namespace inet {
namespace {

// Composite Simpson integration of 2 F(mu) mu over [0, 1]. F is smooth for eta >= 1 (no total
// internal reflection), so 512 intervals give ~1e-9 accuracy.
float integrateFresnelAverage(float eta) {
  constexpr int kIntervals = 512;
  double sum = 0.0;
  for (int i = 0; i <= kIntervals; ++i) {
    double mu = static_cast<double>(i) / kIntervals;
    double w = (i == 0 || i == kIntervals) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    sum += w * 2.0 * mu * fresnelDielectric(static_cast<float>(mu), eta);
  }
  return static_cast<float>(sum / (3.0 * kIntervals));
}

constexpr float kTableMin = 1.0f, kTableMax = 4.0f;
constexpr int kTableSize = 301;  // step 0.01

const std::array<float, kTableSize>& fresnelAverageTable() {
  static const std::array<float, kTableSize> table = [] {
    std::array<float, kTableSize> t{};
    for (int i = 0; i < kTableSize; ++i)
      t[i] = integrateFresnelAverage(kTableMin + (kTableMax - kTableMin) * i / (kTableSize - 1));
    return t;
  }();
  return table;
}

}  // namespace

float fresnelDielectric(float cos_i, float eta, float* cos_t) {
  if (cos_i < 0.0f) {
    cos_i = -cos_i;
    eta = 1.0f / eta;
  }
  cos_i = std::min(cos_i, 1.0f);
  if (eta == 1.0f) {  // no interface
    if (cos_t) *cos_t = cos_i;
    return 0.0f;
  }
  float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) {
    if (cos_t) *cos_t = 0.0f;
    return 1.0f;
  }
  float ct = std::sqrt(1.0f - sin2_t);
  if (cos_t) *cos_t = ct;
  // Both denominators are > 0 here: ct > 0, and eta != 1 rules out cos_i = ct = 0.
  float rs = (cos_i - eta * ct) / (cos_i + eta * ct);
  float rp = (eta * cos_i - ct) / (eta * cos_i + ct);
  return 0.5f * (rs * rs + rp * rp);
}

float fresnelConductor1(float cos_i, float eta, float k) {
  using C = std::complex<float>;
  float c = std::clamp(cos_i, 0.0f, 1.0f);
  C n(eta, k);
  C ct = std::sqrt(C(1.0f) - (1.0f - c * c) / (n * n));
  C ds = c + n * ct, dp = n * c + ct;
  if (std::norm(ds) < 1e-20f || std::norm(dp) < 1e-20f) return 1.0f;  // n = 1 at grazing
  C rs = (c - n * ct) / ds;
  C rp = (n * c - ct) / dp;
  return std::clamp(0.5f * (std::norm(rs) + std::norm(rp)), 0.0f, 1.0f);
}

Vec3f fresnelConductor(float cos_i, const Vec3f& eta, const Vec3f& k) {
  return Vec3f(fresnelConductor1(cos_i, eta.x(), k.x()), fresnelConductor1(cos_i, eta.y(), k.y()),
               fresnelConductor1(cos_i, eta.z(), k.z()));
}

float fresnelDielectricAverage(float eta) {
  if (eta < 1.0f) return 1.0f - eta * eta * (1.0f - fresnelDielectricAverage(1.0f / eta));
  if (eta > kTableMax) return integrateFresnelAverage(eta);
  float x = (eta - kTableMin) / (kTableMax - kTableMin) * (kTableSize - 1);
  int i = std::min(static_cast<int>(x), kTableSize - 2);
  float f = x - static_cast<float>(i);
  const auto& t = fresnelAverageTable();
  return t[i] + f * (t[i + 1] - t[i]);
}

bool refract(const Vec3f& w, const Vec3f& n, float eta, Vec3f& wt) {
  float cos_i = w.dot(n);
  Vec3f nn = n;
  if (cos_i < 0.0f) {  // arriving from below: flip the interface
    cos_i = -cos_i;
    eta = 1.0f / eta;
    nn = -n;
  }
  float sin2_t = std::max(0.0f, 1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) return false;
  float cos_t = std::sqrt(1.0f - sin2_t);
  wt = -w / eta + (cos_i / eta - cos_t) * nn;
  return true;
}

ComplexIor metalIor(Metal metal) {
  switch (metal) {
    case Metal::Gold:
      return {Vec3f(0.1431189557f, 0.3749570432f, 1.4424785571f),
              Vec3f(3.9831604247f, 2.3857207478f, 1.6032152899f)};
    case Metal::Silver:
      return {Vec3f(0.1552646489f, 0.1167232965f, 0.1383806959f),
              Vec3f(4.8283433224f, 3.1222459278f, 2.1469504455f)};
    case Metal::Copper:
      return {Vec3f(0.2004376970f, 0.9240334304f, 1.1022119527f),
              Vec3f(3.9129485033f, 2.4528477015f, 2.1421879552f)};
    case Metal::Aluminium:
      return {Vec3f(1.6574599595f, 0.8803689579f, 0.5212287346f),
              Vec3f(9.2238691996f, 6.2695232477f, 4.8370012281f)};
    case Metal::Chromium:
      return {Vec3f(4.3696828663f, 2.9167024892f, 1.6547005413f),
              Vec3f(5.2064337956f, 4.2313645277f, 3.7549467933f)};
  }
  return {Vec3f::Ones(), Vec3f::Zero()};
}

std::string metalName(Metal metal) {
  switch (metal) {
    case Metal::Gold:
      return "gold";
    case Metal::Silver:
      return "silver";
    case Metal::Copper:
      return "copper";
    case Metal::Aluminium:
      return "aluminium";
    case Metal::Chromium:
      return "chromium";
  }
  return "unknown";
}

}  // namespace inet
