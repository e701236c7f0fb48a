#pragma once
// Trajectory file formats of other datasets and tools, converted at the boundary (STYLE.md 1.8):
// in memory every pose is T_world_camera with our world (right-handed, Z up) and the OpenCV
// camera (x right, y down, z forward); time is int64 ns.
//
// tum        TUM RGB-D `groundtruth.txt`: `t tx ty tz qx qy qz qw`, seconds, w last. Same frames
//            as ours (no conversion). Read/written by trajectory.h.
// euroc      EuRoC/ASL `state_groundtruth_estimate0/data.csv`: `t_ns,px,py,pz,qw,qx,qy,qz`
//            (+ v xyz [m/s], gyro bias xyz [rad/s], accel bias xyz [m/s^2] = 17 columns),
//            integer ns, w first. Reads 8 (TUM-VI mocap) or 17 columns; writes 17 with the
//            velocity from central differences of the positions and zero biases, every number
//            in the shortest form that reads back to the same double (lossless). EuRoC's pose
//            is the IMU body S in the reference R; we store the camera as S (no extrinsic).
// icl        ICL-NUIM `livingRoomN.gt.freiburg`: `frame tx ty tz qx qy qz qw`, the frame
//            number instead of a time (t = frame / icl_fps), no header.
//            This is also what SLAMBench 1.x's checkPos.py compares against (it stops at the
//            first line that is not `int 7*number`, so we never write comments).
// slambench  SLAMBench 2 `groundtruth.txt` (framework/tools/dataset-tools/TUM.cpp): the TUM
//            layout restricted to its regexes: time `digits.digits`, values `[-0-9.]+` (no
//            exponent, no '+'), whitespace separated, '#' comments. The reader rejects what
//            SLAMBench would (CRLF aside, accepted everywhere), so reading checks that a file
//            will load there.
// scenenet_v1  SceneNet v1's `*_trajectory_random_poses_SE3_3x4.txt`: 3x4 camera-to-world
//            [R|t] blocks in the scene's Y-up frame with an OpenGL camera, no times (pose k at
//            k / pose_list_fps); derivation at parseSceneNetV1 in formats.cpp.
// kitti      KITTI odometry poses: 12 numbers a line, camera-to-world [R|t] row-major in the
//            first camera's frame (OpenCV camera, y down), no times (pose k at k / kitti_fps).
//            Derivation at parseKitti in formats.cpp.
// tum        also reads OpenVINS' ov_eval files (8 pose fields + 12 covariance values) and
//            ORB-SLAM3's EuRoC output (TUM layout with nanosecond stamps); euroc also reads
//            VINS-Mono/Fusion's rows (pose, velocity, trailing comma).
// scenenet   SceneNet RGB-D / OppositeRenderer camera log, the text that
//            pySceneNetRGBD/logs_to_protobuf.py turns into scenenet.proto `Pose`s:
//            `time:T pose:x,y,z lookat:x,y,z` one line per pose (seconds, metres); the tool
//            pairs consecutive lines as (shutter_open, shutter_close). `instance:` lines of a
//            render_info.log are skipped.
//
// ICL-NUIM convention (derivation). ICL renders with POV-Ray, whose world is left-handed with
// y up, and publishes K with fy = -480 (living_room_iclnuim README: "the focal length on the
// y-axis is negative"): back-projecting p_c = d K^-1 (u, v, 1) gives a camera frame with x right,
// y UP, z forward, and the .gt.freiburg poses map that frame into POV-Ray's world with a proper
// rotation. With F = diag(1, -1, 1):
//   OpenCV camera:  p_cv = F p_icl_cam
//   our world:      p_w = A p_icl_world,  A = Rx(-90 deg) F = [[1,0,0],[0,0,1],[0,1,0]]
//                   (mirror y to make it right-handed with up = -y, then turn -y onto +z; in
//                   short: swap y and z, so ICL's up y becomes our z and its forward z our y)
//   hence           T_world_camera = [A 0; 0 1] T_icl [F 0; 0 1]   (A, F self-inverse, so
//                   writing applies the same formula). Check: ICL's first lr kt0 pose
//                   `0 0 0 -2.25 0 0 0 1` (identity) becomes a level camera at (0, -2.25, 0)
//                   looking along our +y with image-down along -z.
//
// SceneNet convention. scenenet.proto: "The y vector is defined as [0,1,0]"; its example
// (camera_pose_and_intrinsics_example.py) builds z = lookat - camera, x = z x up, y = z x x:
// an OpenCV camera in a right-handed y-up world. Our world is that one turned by Rx(+90 deg):
// p_w = (x, -z, y)_scenenet. A lookat pair has no roll: reading rebuilds the camera with zero
// roll (image x horizontal), so writing then reading keeps position and viewing direction but
// not roll; a camera looking straight up or down cannot be written (InputError).
#include <optional>
#include <string>

#include "trajectory/trajectory.h"

namespace inet {

enum class TrajectoryFormat { Tum, Euroc, Icl, SlamBench, SceneNet, SceneNetV1, Kitti };

/// Parameters some formats need besides the poses.
struct TrajectoryFormatOptions {
  /// ICL frame rate: time = frame / icl_fps. 30 Hz, the Kinect rate of the ICL-NUIM sequences
  /// (SLAMBench's checkPos.py uses 0.0333 s per frame).
  double icl_fps = 30.0;
  /// scenenet_v1 frame rate: pose k is at k / pose_list_fps (the files hold no times).
  double pose_list_fps = 25.0;
  /// kitti frame rate: pose k is at k / kitti_fps (10 Hz, KITTI odometry's).
  double kitti_fps = 10.0;
};

/// "tum", "euroc", "icl", "slambench", "scenenet", "scenenet_v1", "kitti"; throws InputError("", field, ...) listing
/// the valid names.
TrajectoryFormat parseTrajectoryFormat(const std::string& name,
                                       const std::string& field = "--format");
const char* trajectoryFormatName(TrajectoryFormat f);

/// Guesses from extension and content (a first line of column names is passed over):
/// `time:`/`instance:` lines -> scenenet; comma separated with 17 columns, or 8 with a first
/// field of whole nanoseconds -> euroc; 8 space-separated columns with a .freiburg name -> icl,
/// otherwise -> tum (SLAMBench files read as tum); 4 columns -> scenenet_v1; 12 -> kitti.
/// Throws InputError if it cannot tell.
TrajectoryFormat detectTrajectoryFormat(const std::string& path, const std::string& text);
/// The format an output name implies: .csv euroc, .freiburg icl, .log scenenet, .txt tum.
std::optional<TrajectoryFormat> trajectoryFormatFromExtension(const std::string& path);

/// Reads any supported format (auto-detected when fmt is empty). Every reader throws InputError
/// naming the file and line for a wrong column count, a non-number, a non-unit quaternion (off
/// by > 1e-3), time going back, or an empty file. What real files do and every reader accepts:
/// CRLF, a UTF-8 byte-order mark, scientific notation (read from the digits, so nanoseconds
/// survive), a repeated stamp (the first pose is kept, the rest counted in `report`: see
/// TrajectoryReadReport), and (tum, euroc, icl) a first line of column names without '#'.
/// slambench alone stays as strict as SLAMBench's own regexes.
Trajectory readTrajectory(const std::string& path, std::optional<TrajectoryFormat> fmt = {},
                          const TrajectoryFormatOptions& opt = {},
                          TrajectoryReadReport* report = nullptr);
/// The same on text in memory; `path` only names the source in messages.
Trajectory parseTrajectory(const std::string& text, const std::string& path, TrajectoryFormat fmt,
                           const TrajectoryFormatOptions& opt = {},
                           TrajectoryReadReport* report = nullptr);
/// The file text. Throws InputError when the poses do not fit the format: negative time for
/// euroc/icl/slambench, times off the icl_fps frame grid for icl, a vertical view for scenenet.
std::string formatTrajectory(const Trajectory& traj, TrajectoryFormat fmt,
                             const TrajectoryFormatOptions& opt = {});
/// formatTrajectory written atomically.
void writeTrajectory(const std::string& path, const Trajectory& traj, TrajectoryFormat fmt,
                     const TrajectoryFormatOptions& opt = {});

/// Poses of a second camera rigidly attached to the first: T_world_cam1 = T_world_cam0 *
/// T_cam0_cam1. A stereo rig with baseline b has T_cam0_cam1 = (I, (b, 0, 0)): the right camera
/// sits b metres along the left camera's x axis.
Trajectory offsetTrajectory(const Trajectory& traj, const Pose& T_cam0_cam1);

}  // namespace inet
