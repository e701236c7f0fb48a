#pragma once
// The event camera (issue 6, SENSORS.md section 3): renders the scene at low resolution along the
// camera's B-spline at an adaptive rate and feeds the log intensity to the ESIM-style simulator
// (sensors/event_sim.h).
//
// Each sample is path traced with the same random numbers at every time step (the frame index of
// the sampler stays 0), so that a pixel's Monte Carlo error changes only as its view changes: a
// still camera gives no events, and what noise remains moves with the image rather than flickering
// from sample to sample, which would fire events everywhere. The optional edge-aware denoiser
// (on by default) removes most of it.
//
// Time steps (ESIM's adaptive sampling): the next sample comes after lambda_flow / max image
// speed, the instantaneous optical flow of the rendered depth under the spline's velocity (px/s;
// exact for a static scene). With moving objects (brightness_criterion) also at most
// lambda_brightness / |dL/dt|, dL/dt measured between the last two samples, its 99th percentile
// over pixels rather than ESIM's maximum, so that the Monte Carlo error of a few pixels does not
// set the pace. Measured on the built-in room: with this criterion on in a static scene the
// remaining noise alone held the step at 0.4 ms (2.5 kHz) where the flow asks for about 2 ms.
// Steps are clamped to [min_dt, 1 / min_rate].
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "render/camera.h"
#include "render/lens.h"
#include "sensors/bspline.h"
#include "sensors/event_sim.h"

namespace inet {

class Renderer;

struct EventCameraOptions {
  /// Sensor size: DAVIS240 (240 x 180, the RPG Event-Camera Dataset's camera) by default.
  int width = 240;
  int height = 180;
  int spp = 16;           ///< path-traced samples per pixel of each intensity sample
  int max_bounces = 4;    ///< scattering events per path
  bool denoise = true;    ///< edge-aware denoising of each sample (render/denoise.h)
  double exposure = 1.0;  ///< linear radiance -> intensity I in L = ln(eps + I)
  double lambda_flow = 0.5;        ///< px: the image moves at most this far between samples
  double lambda_brightness = 0.1;  ///< log units: L changes at most this much (<= threshold / 2)
  bool brightness_criterion = false;  ///< also limit steps by dL/dt (scenes with moving objects)
  int64_t min_dt_ns = 100'000;     ///< 10 kHz at most
  double min_rate_hz = 100.0;      ///< at least this many samples per second
  uint64_t seed = 0;               ///< the renderer's seed (the simulator's is sim.seed)
  EventOptions sim;

  /// Throws InputError(source, field, ...) for impossible values (field names as the CLI's).
  void validate(const std::string& source = "") const;
};

/// The event camera's pinhole: `width` x `height` with the horizontal field of view of `K`
/// (square pixels, principal point at the centre), so the events see what cam0 sees.
CameraIntrinsics eventIntrinsics(const CameraIntrinsics& K, int width, int height);

struct EventRunStats {
  size_t samples = 0;      ///< intensity images rendered
  size_t events = 0;
  double wall_s = 0.0;     ///< rendering + simulation
  double render_s = 0.0;   ///< of which rendering
  double min_dt_s = 0.0, max_dt_s = 0.0;  ///< the shortest and longest time step taken
};

/// Called for every intensity sample in time order: time, linear intensity (1 channel, the
/// luminance times `exposure`), and the events of the interval that ends at it (sorted).
using EventSampleSink =
    std::function<void(int64_t t_ns, const ImageF& intensity, const std::vector<Event>& events)>;

/// Simulates the event camera from t_begin_ns to t_end_ns (both inside the spline's range) along
/// `spline` (T_world_camera, OpenCV axes), with `K` the event camera's pinhole. Scene time for
/// moving objects is t - scene_t0_ns. Samples at t_begin and exactly at t_end. `progress`
/// (optional) is called with the fraction of simulated time done.
EventRunStats simulateEventCamera(const Renderer& renderer, const CameraIntrinsics& K,
                                  const PoseSpline& spline, int64_t t_begin_ns, int64_t t_end_ns,
                                  int64_t scene_t0_ns, const EventCameraOptions& opt,
                                  const EventSampleSink& sink,
                                  const std::function<void(double)>& progress = {});

}  // namespace inet
