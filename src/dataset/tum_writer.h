#pragma once
// TUM RGB-D (Freiburg) layout ("tum"), written into the same sequence folder as the ASL files:
//
//   rgb/<ts>.png       colour, 8-bit sRGB RGB
//   depth/<ts>.png     z-depth (fisheye, panorama: ray depth), 16-bit, metres * 5000 (0 = none)
//   rgb.txt depth.txt  3 comment lines, then "<ts> rgb/<ts>.png" rows
//   groundtruth.txt    3 comment lines, then "<ts> tx ty tz qx qy qz qw" (T_world_camera, qw >= 0)
//   associations.txt   "<ts> rgb/<ts>.png <ts> depth/<ts>.png" (associate.py output, no comments)
//   accelerometer.txt  header only (SLAMBench's TUM reader requires the file)
//   camera.txt         "# fx fy cx cy k1 k2 p1 p2 k3" then the values, OpenCV convention;
//                      fisheye "# fx fy cx cy k1 k2 k3 k4 (NOT a pinhole...", panorama
//                      "# fu fv cu cv (NOT a pinhole...": the format itself cannot say so
//
// <ts> is the frame time in seconds with 6 decimals (TUM's own precision), identical for the
// colour image, the depth image and the ground-truth row of one frame. The format needs the rgb
// and depth passes (ray_depth for fisheye and panorama), and frames at least 1 us apart (otherwise
// two frames would share a name). TUM tools do not read camera.txt: without it they assume 525,
// 525, 319.5, 239.5.
#include <memory>
#include <string>

#include "core/pose.h"
#include "dataset/format_writer.h"

namespace inet {

/// "1305031102.175304": seconds with 6 decimals, rounded half up from nanoseconds.
std::string tumStamp(TimeNs t_ns);

/// Factory registered as "tum".
std::unique_ptr<FormatWriter> makeTumWriter(std::shared_ptr<const SequenceContext> ctx);

}  // namespace inet
