#pragma once
// The sensor stage of a sequence (pipeline/sequence_job.h) and of `interiornet events`: which
// sensors a --passes list selects, the per-frame derived passes (Kinect-like depth, optical
// flow) and the event camera run that feeds events0/ (the files: dataset/sequence_writer.h).
#include <filesystem>
#include <functional>
#include <limits>
#include <string>

#include "dataset/sequence_writer.h"
#include "render/camera.h"
#include "render/passes.h"
#include "render/lens.h"
#include "scene/scene.h"
#include "sensors/bspline.h"
#include "sensors/depth_noise.h"
#include "sensors/event_camera.h"
#include "trajectory/trajectory.h"

namespace inet {

class Renderer;

/// What a --passes list asks for: frame passes (render/frame.h) and whole-sequence sensors.
struct SequencePasses {
  PassMask frame = 0;
  bool imu = false;
  bool imu_by_name = false;  ///< asked for by name (else from default/all: dropped when the
                             ///< camera path is too short for a spline)
  bool events = false;
  bool boxes = false;
};

/// Parses --passes: frame pass names (rgb, depth, ..., depth_noisy, flow), imu, events, boxes,
/// "default" (every frame pass, imu and boxes: everything but events) and "all" (everything).
/// What the camera cannot give is an InputError naming --passes when asked for by name, and left
/// out silently from "default" and "all": depth_noisy needs a pinhole (the Kinect model is a
/// pinhole projector-camera pair), flow needs a global shutter (--readout-ms 0), events need a
/// pinhole or thin lens.
SequencePasses parseSequencePasses(const std::string& list, LensType lens, bool rolling_shutter);

/// Options of the event camera as the command line gives them (--event-*, --contrast, ...).
struct EventSettings {
  EventCameraOptions opt;
  double refractory_ms = 0.0;
  double contrast = 0.2;
  double contrast_pos = std::numeric_limits<double>::quiet_NaN();  ///< NaN: contrast
  double contrast_neg = std::numeric_limits<double>::quiet_NaN();
  /// The options (InputError naming the flag), with `seed` for the renderer and the simulator.
  EventCameraOptions options(uint64_t seed) const;
};

/// A neighbouring frame's camera pose and scene time (for the flow).
struct NeighbourFrame {
  Pose T_world_camera;
  TimeNs scene_time_ns = 0;
};
/// Per-frame derived passes of one camera: fills frame.depth_noisy (Pass::DepthNoisy, from
/// depth_z and normal), frame.flow* (Pass::Flow, from depth and instance of `frame` and of a
/// ground-truth render of the next frame) and frame.flow_bwd* (Pass::FlowBackward, the same with
/// the previous frame), as `passes` asks. `noise_frame` keys the depth noise (the frame index;
/// cam1 uses another). Without a next (previous) frame no forward (backward) flow is made.
void deriveFramePasses(const Renderer& renderer, const Scene& scene, const LensModel& lens,
                       PassMask passes, const KinectNoiseOptions& noise, uint64_t seed,
                       uint32_t noise_frame, const NeighbourFrame& self,
                       const NeighbourFrame* previous, const NeighbourFrame* next, Frame& frame);

/// The passes the renderer must make for `passes` (depth and normals for the noisy depth, depth
/// and instance for flow, instance for boxes).
PassMask renderPassesFor(PassMask passes, LensType lens, bool boxes);

/// The event camera over [t_begin_ns, t_end_ns] of `spline` (sensors/event_camera.h, with
/// `K_events` = eventIntrinsics of cam0), each sample streamed into `out` (the sequence folder's
/// events0/, dataset/sequence_writer.h), which is then finished. Steps follow the brightness
/// too when `scene` has moving objects (EventCameraOptions::brightness_criterion). StopRequested
/// names `where` on a signal (events0/ is then left unfinished).
void simulateEvents(EventsFolder& out, const Renderer& renderer, const Scene& scene,
                    const CameraIntrinsics& K_events, const PoseSpline& spline, TimeNs t_begin_ns,
                    TimeNs t_end_ns, TimeNs scene_t0_ns, const EventCameraOptions& opt,
                    bool progress, const std::string& where);

}  // namespace inet
