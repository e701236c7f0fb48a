#pragma once
// Shared fixtures for the dataset tests: a private temporary folder, a synthetic 3-frame
// sequence whose pixel values are chosen so that every encoding has an exact, independently
// computable expectation, and small file helpers.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "../temp_dir.h"
#include "dataset/sequence_writer.h"
#include "render/camera.h"
#include "render/passes.h"
#include "trajectory/trajectory.h"

namespace inet::test {

namespace fs = std::filesystem;

inline std::string readBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline std::vector<std::string> readLines(const fs::path& p) {
  std::vector<std::string> lines;
  std::istringstream in(readBytes(p));
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

/// Every regular file under `root` (relative path -> bytes).
inline std::map<std::string, std::string> readTree(const fs::path& root) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(root))
    if (e.is_regular_file()) files[fs::relative(e.path(), root).string()] = readBytes(e.path());
  return files;
}

inline CameraIntrinsics smallCamera() {
  CameraIntrinsics K;
  K.width = 24;
  K.height = 16;
  K.fx = 20.0;
  K.fy = 21.5;
  K.cx = 12.0;  // renderer convention: OpenCV cx = 11.5
  K.cy = 8.0;
  return K;
}

/// The integer depth code (in 1/5000 m) of pixel (x, y) of frame k; depth_z = code / 5000 m.
/// Pixel (0, 0) has no surface.
inline int depthCode5000(int x, int y, int k) {
  return (x == 0 && y == 0) ? 0 : 5000 + 97 * x + 13 * y + 7 * k;
}

/// A frame with every pass, deterministic in (x, y, k).
inline Frame syntheticFrame(const CameraIntrinsics& K, int k) {
  Frame f;
  f.passes = kRenderPasses;
  f.rgb = ImageF(K.width, K.height, 3);
  f.albedo = ImageF(K.width, K.height, 3);
  f.shading = ImageF(K.width, K.height, 3, 0.25f);
  f.depth_z = ImageF(K.width, K.height, 1);
  f.depth_ray = ImageF(K.width, K.height, 1);
  f.normal = ImageF(K.width, K.height, 3);
  f.label = ImageU8(K.width, K.height, 1);
  f.instance = ImageU16(K.width, K.height, 1);
  for (int y = 0; y < K.height; ++y)
    for (int x = 0; x < K.width; ++x) {
      for (int c = 0; c < 3; ++c) {
        f.rgb.at(x, y, c) = static_cast<float>((x + 2 * y + 5 * c + k) % 29) / 24.0f;  // some > 1
        f.albedo.at(x, y, c) = static_cast<float>((3 * x + y + c) % 17) / 16.0f;
      }
      const int code = depthCode5000(x, y, k);
      f.depth_z.at(x, y) = static_cast<float>(code / 5000.0);
      f.depth_ray.at(x, y) = f.depth_z.at(x, y) * (1.0f + 0.001f * x);
      if (code != 0) {
        double a = 0.1 * x + 0.05 * k, b = 0.07 * y;
        f.normal.at(x, y, 0) = static_cast<float>(std::sin(a) * std::cos(b));
        f.normal.at(x, y, 1) = static_cast<float>(std::sin(b));
        f.normal.at(x, y, 2) = static_cast<float>(-std::cos(a) * std::cos(b));
      }
      f.label.at(x, y) = static_cast<uint8_t>((x / 4 + y / 4 + k) % 41);
      f.instance.at(x, y) = static_cast<uint16_t>(1000 * k + 300 * x + y);  // exceeds 255
    }
  return f;
}

/// Three poses 40 ms apart starting at an EuRoC-like epoch; the middle quaternion is given with
/// w < 0 so the writers must flip its sign.
inline Trajectory syntheticTrajectory(int frames = 3) {
  Trajectory traj;
  for (int k = 0; k < frames; ++k) {
    TimedPose p;
    p.t_ns = 1403715273262142976LL + 40000000LL * k + (k == 2 ? 123 : 0);
    Eigen::AngleAxisd aa(0.3 + 0.2 * k, Vec3(0.2, -0.5, 1.0).normalized());
    Quat q(aa);
    if (k == 1) q.coeffs() = -q.coeffs();
    p.T_world_camera.q = q;
    p.T_world_camera.t = Vec3(1.0 + 0.05 * k, -2.0 + 0.01 * k * k, 1.5);
    traj.poses.push_back(p);
  }
  return traj;
}

inline SequenceSpec syntheticSpec(const fs::path& dir, PassMask passes = kRenderPasses) {
  SequenceSpec spec;
  spec.dir = dir;
  spec.intrinsics = smallCamera();
  spec.passes = passes;
  spec.meta = {{"seed", 42}, {"command_line", "interiornet generate --test"}};
  return spec;
}

/// Writes the synthetic sequence (all frames, then finish) and returns the frame count.
inline size_t writeSyntheticSequence(const fs::path& dir, const std::vector<std::string>& formats,
                                     PassMask passes = kRenderPasses) {
  Trajectory traj = syntheticTrajectory();
  SequenceWriter w(syntheticSpec(dir, passes), traj, formats);
  for (size_t k = 0; k < w.frameCount(); ++k)
    w.writeFrame(k, syntheticFrame(smallCamera(), static_cast<int>(k)));
  w.finish();
  return w.frameCount();
}

}  // namespace inet::test
