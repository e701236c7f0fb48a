#pragma once
// Ground-truth passes from one ray through each pixel centre, traced in coherent 16-wide packets
// (4x4 pixel blocks; Embree's rtcIntersect16). Exact by construction: no filtering, no jitter.
//   depth    z-depth (metres along the optical axis) = the ray parameter, since the camera-frame
//            direction has z = 1
//   ray_depth Euclidean distance from the camera centre (the InteriorNet paper's depth)
//   normal   unit shading normal in the camera frame (the mesh's interpolated vertex normals, else
//            the geometric normal; normal maps are left out), flipped to face the camera
//   label    NYU40 class; instance: instance id; albedo: linear diffuse reflectance, textured
//            (mip level from the pixel's footprint, as the path tracer reads it)
#include "core/pose.h"
#include "render/camera.h"
#include "render/embree_scene.h"
#include "render/passes.h"
#include "render/integrator.h"
#include "render/lens.h"

namespace inet {

/// Fills the ground-truth images of `frame` selected by `passes` (the RGB bit is ignored).
/// Images are (re)allocated to the camera size. Runs in parallel over tiles (TBB).
/// Any lens model: rays come from generateRay at the pixel centre through the lens centre (the
/// in-focus chief ray of a thin lens). `depth` is the camera-frame z of the hit (0 if behind the
/// camera), `ray_depth` its distance from the ray origin; pixels without a ray (outside a
/// fisheye circle) are 0 in every pass.
/// With `exposure` (not null, moving), each row is traced from the pose at the middle of that
/// row's exposure, so rolling-shutter ground truth matches the rolling-shutter image.
void renderGroundTruth(const EmbreeScene& scene, const LensModel& lens, const Pose& T_world_camera,
                       PassMask passes, Frame& frame, const CameraExposure* exposure = nullptr);

}  // namespace inet
