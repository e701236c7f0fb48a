#include "sensors/temporal_reuse.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "core/color.h"
#include "core/error.h"
#include "render/bsdf.h"
#include "scene/scene.h"

namespace inet {
namespace {

/// 1 where a pixel's samples, spread over its footprint, all land on one continuous surface: its
/// 3x3 neighbourhood has depth, one NYU40 class, depths within 5 % of the centre's and, in a
/// scene with moving objects, one instance. Edge pixels mix two surfaces in proportions that
/// change from frame to frame (the wall behind a mirror's rim would leak into the mirror), so
/// they neither give nor take reused light. The class, not the instance, joins the pieces of one
/// surface: a wall is many instances, some coplanar and overlapping (their boundary pixels
/// flicker between ids), and the reuse of those pixels is exact all the same.
ImageU8 interiorPixels(const ImageU8& label, const ImageU16* instance, const ImageF& depth) {
  const int W = label.width, H = label.height;
  ImageU8 out(W, H, 1, 0);
  for (int y = 1; y + 1 < H; ++y)
    for (int x = 1; x + 1 < W; ++x) {
      const float z = depth.at(x, y);
      if (!(z > 0.f)) continue;
      bool same = true;
      for (int dy = -1; dy <= 1 && same; ++dy)
        for (int dx = -1; dx <= 1 && same; ++dx)
          same = label.at(x + dx, y + dy) == label.at(x, y) &&
                 std::abs(depth.at(x + dx, y + dy) - z) <= 0.05f * z &&
                 (!instance || instance->at(x + dx, y + dy) == instance->at(x, y));
      out.at(x, y) = same ? 1 : 0;
    }
  return out;
}

/// TemporalReuseOptions::firefly_ratio: an interior pixel whose luminance in `irradiance` is more
/// than `ratio` times that of every one of its 8 neighbours (one surface, as it is interior)
/// takes the irradiance and variance of the neighbour of median luminance (loneBrightPixels).
/// Returns how many pixels it changed and the share of the image's luminance they lost.
TemporalReuse::Fireflies rejectFireflies(const ImageU8& interior, float ratio, ImageF& irradiance,
                                         ImageF& variance) {
  if (!(ratio > 0.f)) return {};
  std::vector<float> l(irradiance.data.size() / 3);
  double total = 0.0;
  for (size_t i = 0; i < l.size(); ++i) {
    l[i] = luminance(
        Vec3f(irradiance.data[3 * i], irradiance.data[3 * i + 1], irradiance.data[3 * i + 2]));
    total += l[i];
  }
  TemporalReuse::Fireflies out;
  double removed = 0.0;
  for (const PixelSwap& s : loneBrightPixels(irradiance.width, irradiance.height, l.data(),
                                             interior.data.data(), nullptr, ratio, 8)) {
    for (int c = 0; c < 3; ++c) {
      irradiance.data[3 * s.pixel + c] = irradiance.data[3 * s.with + c];
      variance.data[3 * s.pixel + c] = variance.data[3 * s.with + c];
    }
    removed += static_cast<double>(l[s.pixel]) - l[s.with];
    ++out.pixels;
  }
  out.light_share = total > 0.0 ? removed / total : 0.0;
  return out;
}

}  // namespace

void TemporalReuseOptions::validate(const std::string& where) const {
  if (window < 1 || window > 64)
    throw InputError(where, "--temporal", fmt::format("window {} is outside 1..64 frames", window));
  if (boost < 1 || boost > 16)
    throw InputError(where, "--history-boost", fmt::format("{} is outside 1..16", boost));
  if (boost_edges < 1 || boost_edges > 16)
    throw InputError(where, "--history-boost-edges",
                     fmt::format("{} is outside 1..16", boost_edges));
  if (!(albedo_epsilon > 0.f && albedo_epsilon <= 1.f))
    throw InputError(where, "temporal.albedo_epsilon", "must be in (0, 1]");
  if (!(view_turn >= 0.f && view_turn <= 4.f))
    throw InputError(where, "temporal.view_turn", "must be in [0, 4] (units of the lobe's alpha)");
  if (smooth < 1 || smooth > 64)
    throw InputError(where, "--temporal-smooth", fmt::format("{} is outside 1..64 frames", smooth));
  if (!(firefly_ratio == 0.f || (firefly_ratio >= 2.f && firefly_ratio <= 1e6f)))
    throw InputError(where, "--temporal-firefly",
                     fmt::format("{} is neither 0 (off) nor in 2..1e6", firefly_ratio));
  flow.validate(where);
}

std::string TemporalReuseOptions::describe() const {
  return fmt::format(
      "window={} boost={} boost_edges={} albedo_epsilon={} view_turn={} smooth={} "
      "firefly_ratio={} occlusion_rel_tol={} occlusion_abs_tol_m={}",
      window, boost, boost_edges, albedo_epsilon, view_turn, smoothFrames(), firefly_ratio,
      flow.occlusion_rel_tol, flow.occlusion_abs_tol_m);
}

TemporalReuse::TemporalReuse(const Scene& scene, const LensModel& lens,
                             const TemporalReuseOptions& options)
    : scene_(scene), lens_(lens), options_(options) {
  options_.validate("temporal reuse");
  options_.flow.depth_kind = groundTruthDepthKind(lens.type);
  for (const Object& o : scene.objects) has_motion_ = has_motion_ || o.moving();
}

const ImageF& TemporalReuse::depthOf(const Frame& f) const {
  return options_.flow.depth_kind == DepthKind::ZDepth ? f.depth_z : f.depth_ray;
}

TemporalReuse::Past TemporalReuse::geometryOf(const Frame& f, const Pose& T_world_camera,
                                              double scene_time_s) const {
  const ImageF& depth = depthOf(f);
  INET_CHECK(depth.width == lens_.K.width && depth.height == lens_.K.height &&
             f.label.width == lens_.K.width && (!has_motion_ || f.instance.width == lens_.K.width));
  // instances matter to the visibility test and the taps only where objects move (the motion
  // is per instance); otherwise the class and the depths decide (see interiorPixels)
  const ImageU16* instance = has_motion_ ? &f.instance : nullptr;
  return Past{T_world_camera, scene_time_s, depth, instance ? *instance : ImageU16(), f.label,
              {}, {}, interiorPixels(f.label, instance, depth), {}, {}, {}, {}, {}};
}

TemporalReuse::Reprojection TemporalReuse::reproject(const Frame& f, const Pose& T_world_camera,
                                                     double scene_time_s) const {
  const int W = lens_.K.width, H = lens_.K.height;
  const size_t n_px = static_cast<size_t>(W) * H;
  Reprojection r{geometryOf(f, T_world_camera, scene_time_s), {}, {}};
  const Past& self = r.self;
  // Where each interior pixel lands in each remembered frame: the (up to) 4 bilinear taps around
  // the landing point that are interior pixels of the pixel's own class (and instance, where
  // objects move; the flow's visibility rule has checked their depths), with weights summing to
  // 1; none where the point is not seen there.
  r.source.resize(past_.size());
  r.turn.resize(past_.size());
  const FlowFrameView now{self.depth, self.instance, T_world_camera};
  // each interior pixel's point in the world (NaN where it has none), for the view's turn
  std::vector<Vec3f> point(n_px, Vec3f::Constant(std::numeric_limits<float>::quiet_NaN()));
  tbb::parallel_for(tbb::blocked_range<int>(0, H), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < W; ++x) {
        Vec3 p_cam;
        if (self.interior.at(x, y) &&
            backProjectPixel(lens_, options_.flow.depth_kind, x, y, self.depth.at(x, y), p_cam))
          point[static_cast<size_t>(y) * W + x] = (T_world_camera * p_cam).cast<float>();
      }
  });
  const Vec3f centre = T_world_camera.t.cast<float>();
  const bool wrap_u = lens_.type == LensType::Panorama;
  for (size_t j = 0; j < past_.size(); ++j) {
    const Past& p = past_[j];
    const ObjectMotion motion =
        has_motion_ ? objectMotionBetween(scene_, scene_time_s, p.scene_time_s) : ObjectMotion{};
    const FlowField fl = forwardFlow(now, FlowFrameView{p.depth, p.instance, p.T_world_camera},
                                     lens_, motion, options_.flow);
    std::vector<Taps>& src = r.source[j];
    src.assign(n_px, Taps{});
    std::vector<float>& turn = r.turn[j];
    turn.assign(n_px, std::numeric_limits<float>::infinity());
    const Vec3f centre_j = p.T_world_camera.t.cast<float>();
    tbb::parallel_for(tbb::blocked_range<int>(0, H), [&](const tbb::blocked_range<int>& rows) {
      for (int y = rows.begin(); y < rows.end(); ++y)
        for (int x = 0; x < W; ++x) {
          if (!fl.valid.at(x, y) || fl.occluded.at(x, y) || !self.interior.at(x, y)) continue;
          // pixel centres at +0.5: the taps are the centres around the landing point
          const double u = x + fl.flow.at(x, y, 0), v = y + fl.flow.at(x, y, 1);
          const double u0 = std::floor(u), v0 = std::floor(v);
          const auto fu = static_cast<float>(u - u0), fv = static_cast<float>(v - v0);
          const uint16_t inst = has_motion_ ? f.instance.at(x, y) : 0;
          const uint8_t cls = f.label.at(x, y);
          Taps& t = src[static_cast<size_t>(y) * W + x];
          float total = 0.f;
          for (int k = 0; k < 4; ++k) {
            int tu = static_cast<int>(u0) + (k & 1);
            const int tv = static_cast<int>(v0) + (k >> 1);
            const float w = ((k & 1) ? fu : 1.f - fu) * ((k >> 1) ? fv : 1.f - fv);
            if (wrap_u) tu = ((tu % W) + W) % W;
            if (w <= 0.f || tu < 0 || tu >= W || tv < 0 || tv >= H) continue;
            if (p.label.at(tu, tv) != cls || !p.interior.at(tu, tv) ||
                (has_motion_ && p.instance.at(tu, tv) != inst))
              continue;
            t.index[t.count] = tv * W + tu;
            t.weight[t.count++] = w;
            total += w;
          }
          for (int k = 0; k < t.count; ++k) t.weight[k] /= total;
          // the view's turn at the point (a moving object's points stay at infinity)
          const Vec3f& X = point[static_cast<size_t>(y) * W + x];
          if (t.count > 0 && (!has_motion_ || !motion.delta.count(inst)) && X.allFinite()) {
            const Vec3f a = centre - X, b = centre_j - X;
            turn[static_cast<size_t>(y) * W + x] = std::atan2(a.cross(b).norm(), a.dot(b));
          }
        }
    });
  }
  return r;
}

const ImageU8& TemporalReuse::plan(const Frame& gt, const Pose& T_world_camera,
                                   double scene_time_s) {
  added_ = Added{};  // the previous frame's smoothing is over
  planned_ = std::make_unique<Reprojection>(reproject(gt, T_world_camera, scene_time_s));
  // the samples multiplier: more where fewer remembered frames will give reused light
  const std::vector<std::vector<Taps>>& source = planned_->source;
  const ImageU8& interior = planned_->self.interior;
  planned_multiplier_ = ImageU8(interior.width, interior.height, 1, 1);
  for (size_t i = 0; i < interior.data.size(); ++i) {
    int seen = 0;
    for (const std::vector<Taps>& src : source) seen += src[i].count > 0 ? 1 : 0;
    planned_multiplier_.data[i] = static_cast<uint8_t>(
        interior.data[i] ? std::max(1, options_.boost - seen) : options_.boost_edges);
  }
  return planned_multiplier_;
}

float TemporalReuse::maxTurn(float view_alpha) const {
  return view_alpha >= kNoViewDependentLobe ? std::numeric_limits<float>::infinity()
                                            : options_.view_turn * view_alpha;
}

void TemporalReuse::addGeometry(const Frame& gt, const Pose& T_world_camera, double scene_time_s) {
  remember(geometryOf(gt, T_world_camera, scene_time_s));
  planned_.reset();
  added_ = Added{};
}

void TemporalReuse::remember(Past&& p) {
  past_.push_back(std::move(p));
  while (static_cast<int>(past_.size()) > options_.window - 1) past_.pop_front();
}

void TemporalReuse::add(Frame& frame, RgbLayers& layers, const Pose& T_world_camera,
                        double scene_time_s, ImageU8* used) {
  const int W = lens_.K.width, H = lens_.K.height;
  const ImageF& depth = depthOf(frame);
  INET_CHECK(frame.rgb.width == W && frame.rgb.height == H && layers.albedo.width == W &&
                 depth.width == W && frame.label.width == W && frame.instance.width == W &&
                 layers.diffuse.width == W && layers.diffuse_variance.width == W &&
                 layers.rest_variance.width == W && layers.emission.width == W &&
                 layers.view_alpha.width == W && layers.view_alpha.channels == 1);
  // (a frame rendered with layers, at the lens' size)
  const float eps = options_.albedo_epsilon;
  const size_t n_px = static_cast<size_t>(W) * H;
  // the reprojection plan() made for this frame (its ground truth is this frame's), else now;
  // without a plan the frame was rendered at multiplier 1
  std::unique_ptr<Reprojection> r = std::move(planned_);
  ImageU8 multiplier = std::move(planned_multiplier_);
  if (!r || !(r->self.T_world_camera.t == T_world_camera.t) ||
      !(r->self.T_world_camera.q.coeffs() == T_world_camera.q.coeffs()) ||
      r->self.scene_time_s != scene_time_s) {
    r = std::make_unique<Reprojection>(reproject(frame, T_world_camera, scene_time_s));
    multiplier = ImageU8();
  }
  Past self = std::move(r->self);
  self.multiplier = std::move(multiplier);
  self.irradiance = ImageF(W, H, 3);
  self.variance = ImageF(W, H, 3);
  self.rest = ImageF(W, H, 3);
  self.rest_variance = layers.rest_variance;
  // this frame's demodulated diffuse light and its view-dependent light: what later frames read
  for (size_t i = 0; i < n_px * 3; ++i) {
    const float a = std::max(layers.albedo.data[i], eps);
    self.irradiance.data[i] = layers.diffuse.data[i] / a;
    self.variance.data[i] = layers.diffuse_variance.data[i] / (a * a);
    self.rest.data[i] = frame.rgb.data[i] - layers.emission.data[i] - layers.diffuse.data[i];
  }
  // one bright sample must not stay in the window (see the top of temporal_reuse.h)
  fireflies_ =
      rejectFireflies(self.interior, options_.firefly_ratio, self.irradiance, self.variance);
  auto samplesOf = [](const Past& p, size_t i) {  // the multiplier pixel i was rendered with
    return p.multiplier.data.empty() ? 1.0 : std::max<double>(1.0, p.multiplier.data[i]);
  };
  const std::vector<std::vector<Taps>>& source = r->source;
  const std::vector<std::vector<float>>& turn = r->turn;
  if (used) *used = ImageU8(W, H, 1, 1);
  ImageF& rgb = frame.rgb;
  tbb::parallel_for(tbb::blocked_range<int>(0, H), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < W; ++x) {
        const size_t i = static_cast<size_t>(y) * W + x;
        // Each frame's estimate is weighted by the inverse of its variance factor: 1 / m for
        // this frame's own pixel (m its samples multiplier), sum w^2 / m for an interpolation of
        // a past frame's taps, every sample taken as having the same noise. The weights depend
        // only on geometry, never on the samples, so the mean stays unbiased. The rest (view-
        // dependent light) takes the frames whose view has turned little enough, with the same
        // weights and its own total.
        const double own = samplesOf(self, i);
        const float max_turn = maxTurn(layers.view_alpha.data[i]);
        double sum[3], var[3], total = own;
        double rest_sum[3], rest_var[3], rest_total = own;
        for (int c = 0; c < 3; ++c) {
          sum[c] = own * self.irradiance.data[i * 3 + c];
          var[c] = own * own * self.variance.data[i * 3 + c];
          rest_sum[c] = own * self.rest.data[i * 3 + c];
          rest_var[c] = own * own * self.rest_variance.data[i * 3 + c];
        }
        int n = 1, n_rest = 1;
        // newest first: a fixed order, so the sums do not depend on threads
        for (size_t j = past_.size(); j-- > 0;) {
          const Taps& t = source[j][i];
          if (t.count == 0 || past_[j].irradiance.data.empty()) continue;
          double s2 = 0.0;
          for (int k = 0; k < t.count; ++k)
            s2 += static_cast<double>(t.weight[k]) * t.weight[k] /
                  samplesOf(past_[j], static_cast<size_t>(t.index[k]));
          const double frame_w = 1.0 / s2;
          const bool rest_too = turn[j][i] <= max_turn;
          for (int c = 0; c < 3; ++c) {
            double value = 0.0, value_var = 0.0, r_value = 0.0, r_var = 0.0;
            for (int k = 0; k < t.count; ++k) {
              const size_t at = static_cast<size_t>(t.index[k]) * 3 + c;
              const double w2 = static_cast<double>(t.weight[k]) * t.weight[k];
              value += t.weight[k] * past_[j].irradiance.data[at];
              value_var += w2 * past_[j].variance.data[at];
              if (rest_too) {
                r_value += t.weight[k] * past_[j].rest.data[at];
                r_var += w2 * past_[j].rest_variance.data[at];
              }
            }
            sum[c] += frame_w * value;
            var[c] += frame_w * frame_w * value_var;
            rest_sum[c] += frame_w * r_value;
            rest_var[c] += frame_w * frame_w * r_var;
          }
          total += frame_w;
          ++n;
          if (rest_too) {
            rest_total += frame_w;
            ++n_rest;
          }
        }
        if (used) used->at(x, y) = static_cast<uint8_t>(n);
        if (n == 1) continue;  // seen for the first time: the frame's own samples, untouched
        for (int c = 0; c < 3; ++c) {
          const size_t k = i * 3 + c;
          const float a = std::max(layers.albedo.data[k], eps);
          const auto reused = static_cast<float>(sum[c] / total * a);
          const auto reused_var = static_cast<float>(var[c] / (total * total) * a * a);
          rgb.data[k] += reused - layers.diffuse.data[k];
          layers.diffuse.data[k] = reused;
          layers.diffuse_variance.data[k] = reused_var;
          if (n_rest > 1) {
            rgb.data[k] += static_cast<float>(rest_sum[c] / rest_total) - self.rest.data[k];
            layers.rest_variance.data[k] =
                static_cast<float>(rest_var[c] / (rest_total * rest_total));
          }
          // the rest's variance plus the reused diffuse light's (their covariance left out: the
          // reused part is mostly other frames' independent samples)
          layers.variance.data[k] = reused_var + layers.rest_variance.data[k];
        }
      }
  });
  const size_t before = past_.size();
  remember(std::move(self));
  // kept for smooth() only: the taps are the largest thing here (36 bytes per pixel and frame)
  if (options_.smoothFrames() > 1) added_ = Added{std::move(*r), before + 1 - past_.size()};
}

void TemporalReuse::smooth(Frame& frame, const RgbLayers& layers, bool split) {
  const int M = options_.smoothFrames();
  if (M <= 1) return;
  const int W = lens_.K.width, H = lens_.K.height;
  INET_CHECK(frame.rgb.width == W && frame.rgb.height == H && layers.emission.width == W &&
             layers.albedo.width == W && layers.view_alpha.width == W &&
             (!split || layers.diffuse.width == W));
  // smooth() follows the add() of the same frame, whose taps added_ holds
  INET_CHECK(!past_.empty() &&
             added_.reprojection.source.size() + 1 == past_.size() + added_.popped);
  const float eps = options_.albedo_epsilon;
  const size_t n_px = static_cast<size_t>(W) * H;
  Past& self = past_.back();
  // split: the diffuse light demodulated and the rest as it is; else the whole light demodulated
  self.filtered = ImageF(W, H, 3);
  self.filtered_rest = split ? ImageF(W, H, 3) : ImageF();
  for (size_t i = 0; i < n_px * 3; ++i) {
    const float light = frame.rgb.data[i] - layers.emission.data[i];
    const float diffuse = split ? layers.diffuse.data[i] : light;
    self.filtered.data[i] = diffuse / std::max(layers.albedo.data[i], eps);
    if (split) self.filtered_rest.data[i] = light - diffuse;
  }
  const std::vector<std::vector<Taps>>& source = added_.reprojection.source;
  const std::vector<std::vector<float>>& turn = added_.reprojection.turn;
  const size_t remembered = past_.size() - 1;  // the frames before this one
  const size_t first = remembered - std::min(remembered, static_cast<size_t>(M - 1));
  // older frames will not be within the last M again
  for (size_t j = 0; j < first; ++j) past_[j].filtered = past_[j].filtered_rest = ImageF();
  auto interpolate = [](const Taps& t, const ImageF& image, int c) {
    double value = 0.0;
    for (int k = 0; k < t.count; ++k)
      value += t.weight[k] * image.data[static_cast<size_t>(t.index[k]) * 3 + c];
    return value;
  };
  tbb::parallel_for(tbb::blocked_range<int>(0, H), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < W; ++x) {
        const size_t i = static_cast<size_t>(y) * W + x;
        const float max_turn = maxTurn(layers.view_alpha.data[i]);
        double sum[3], rest[3];
        for (int c = 0; c < 3; ++c) {
          sum[c] = self.filtered.data[3 * i + c];
          rest[c] = split ? self.filtered_rest.data[3 * i + c] : 0.0;
        }
        int n = 1, n_rest = 1;
        // newest first (a fixed order); past_[j] is source[j + popped]'s frame
        for (size_t j = remembered; j-- > first;) {
          const size_t s = j + added_.popped;
          const Taps& t = source[s][i];
          // a frame smoothed the other way holds the other light in `filtered`
          if (t.count == 0 || past_[j].filtered.data.empty() ||
              past_[j].filtered_rest.data.empty() == split)
            continue;
          const bool turned_little = turn[s][i] <= max_turn;
          if (split || turned_little) {
            for (int c = 0; c < 3; ++c) sum[c] += interpolate(t, past_[j].filtered, c);
            ++n;
          }
          if (split && turned_little) {
            for (int c = 0; c < 3; ++c) rest[c] += interpolate(t, past_[j].filtered_rest, c);
            ++n_rest;
          }
        }
        if (n == 1 && n_rest == 1) continue;
        for (int c = 0; c < 3; ++c) {
          const size_t k = i * 3 + c;
          frame.rgb.data[k] = layers.emission.data[k] +
                              static_cast<float>(sum[c] / n) * std::max(layers.albedo.data[k], eps) +
                              static_cast<float>(rest[c] / n_rest);
        }
      }
  });
  added_ = Added{};  // done with its taps
}

}  // namespace inet
