#pragma once
// ASL / EuRoC MAV layout ("asl"). The sequence folder plays the role of EuRoC's "mav0" folder (no
// extra mav0/ level); point EuRoC readers at the sequence folder itself.
//
//   body.yaml                                  comment only; body frame B = cam0 frame
//   cam0/data/<t>.png        sensor.yaml data.csv   colour, 8-bit sRGB RGB
//   cam0/data/<t>.exr                               spec.rgb_exr: linear RGB, float, R G B
//   depth0/data/<t>.png      sensor.yaml data.csv   z-depth (fisheye, panorama: ray depth), mm
//   depth0/data/<t>.exr                             Euclidean ray depth, float metres, channel Z
//   normal0/data/<t>.png     sensor.yaml data.csv   camera-frame normals, 16-bit RGB
//   albedo0/data/<t>.png     sensor.yaml data.csv   diffuse albedo, 8-bit sRGB RGB
//   label0/data/<t>_nyu.png  sensor.yaml data.csv   NYU40 class, 8-bit grey
//   label0/data/<t>_instance.png                    instance id, 16-bit grey
//   depth0_noisy/data/<t>.png sensor.yaml data.csv  Kinect-like z-depth, mm
//   flow0/data/<t>.flo .png .exr _occ.png  sensor.yaml data.csv   forward flow (not the last
//                                                   frame); of .flo .png .exr those in spec.storage
//   cam1/ depth1/ ... label1/ ...                   with spec.stereo_baseline_m: cam1's twins
//   state_groundtruth_estimate0/data.csv sensor.yaml   17-column EuRoC ground truth
//
// <t> is the frame time in integer nanoseconds, zero-padded to 19 digits (EuRoC's width), used
// both in file names and in the timestamp column. Only the passes in spec.passes are written;
// a folder with no pass is not created. Every image folder is registered to cam0 and shares its
// intrinsics (sensor.yaml states them in the OpenCV convention) and lens: pinhole and thin lens
// as Kalibr pinhole + radial-tangential, fisheye as Kalibr pinhole + equidistant (r = f theta),
// panorama as "camera_model: equirectangular" with the pixel mapping in comments.
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/pose.h"
#include "dataset/format_writer.h"

namespace inet {

/// Header of every camera data.csv (EuRoC, verbatim).
inline constexpr const char* kEurocCameraCsvHeader = "#timestamp [ns],filename";
/// Header of state_groundtruth_estimate0/data.csv (EuRoC, verbatim; note the spaces).
inline constexpr const char* kEurocGroundTruthCsvHeader =
    "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], "
    "q_RS_z [], v_RS_R_x [m s^-1], v_RS_R_y [m s^-1], v_RS_R_z [m s^-1], b_w_RS_S_x [rad s^-1], "
    "b_w_RS_S_y [rad s^-1], b_w_RS_S_z [rad s^-1], b_a_RS_S_x [m s^-2], b_a_RS_S_y [m s^-2], "
    "b_a_RS_S_z [m s^-2]";

/// "0000000001403715273" style stem: nanoseconds zero-padded to 19 digits (t_ns >= 0).
std::string aslStamp(TimeNs t_ns);

/// A sensor.yaml T_BS block (sensor -> body) for a sensor translated by t from the body frame,
/// same orientation; EuRoC's layout ("T_BS:", cols, rows, data in 4 rows).
std::string translationTbs(const Vec3& t);

/// One row of an ASL data.csv: the stamp and the file it names.
struct SequenceFrame {
  TimeNs t_ns = 0;
  std::string stamp;  ///< the stamp as written, 19 digits: the stem of every file of the frame
  std::string file;   ///< the file it names in <sensor>/data/ (no folder)
};

/// Rows of an ASL `<sensor>/data.csv` (`#timestamp [ns],filename`): every line checked, stamps
/// strictly increasing; InputError naming the file and line otherwise, or when it lists nothing.
std::vector<SequenceFrame> readAslFrameList(const std::filesystem::path& csv);

/// The `comment:` of <folder>/sensor.yaml for the folders whose comment depends on nothing but
/// the folder (normal0, albedo0, shading0, label0, depth0_noisy, flow0, flow0_bwd); "" for others.
std::string aslSensorComment(std::string_view folder);

/// Factory registered as "asl".
std::unique_ptr<FormatWriter> makeAslWriter(std::shared_ptr<const SequenceContext> ctx);

}  // namespace inet
