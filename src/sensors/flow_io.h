#pragma once
// Optical flow files (SENSORS.md section 5). Both hold a FlowField's flow and valid mask (not the
// occlusion mask); which flow a file holds is told by its name (flow_fwd_* two-frame forward
// k -> k+1, flow_inst_* instantaneous px/s), not by the format.
//
//  Middlebury .flo (Baker et al., IJCV 2011; flow-code/README.txt): little-endian;
//    bytes 0-3   float32 tag 202021.25 ("PIEH" in ASCII)
//    bytes 4-7   int32 width, bytes 8-11 int32 height
//    then width * height * 2 float32, (u, v) interleaved, row-major from the top row.
//    Unknown flow: written as u = v = 1e10; read as unknown when |u| or |v| > 1e9 or not finite.
//  KITTI flow PNG (Geiger et al., devkit io_flow.h): 16-bit RGB PNG,
//    R = 64 u + 2^15, G = 64 v + 2^15, B = valid (1) or not (0); decode u = (R - 2^15) / 64.
//    We round to the nearest 1/64 px (the devkit truncates; both decode identically) and clamp to
//    [0, 65535], i.e. |flow| is representable up to 512 px. Invalid pixels are (0, 0, 0). A pixel
//    reads as valid when B > 0 (as the devkit's isValid).
//  Flow EXR (ours; what the .flo holds, compressed): a scanline EXR with float32 channels U and
//    V; unknown flow is NaN. Lossless like .flo, a fraction of its size (docs/output.md 9).
//
// Writers are atomic (a temporary renamed into place, core/atomic_file.h) and deterministic;
// failures (unwritable folder, wrong image shape) are InputErrors naming the path. Readers throw
// InputError(path, field, problem) for malformed files, field one of "tag", "width", "height",
// "size" (.flo) or "channels" (PNG; bit depth and PNG decoding errors come from core/image_io).
// Pixel convention as FlowField: flow in pixels, +u right, +v down; u, v are differences of
// positions, so the pixel-centre convention (renderer +0.5 vs OpenCV integer) does not matter.
#include <filesystem>

#include "core/image_io.h"
#include "sensors/optical_flow.h"

namespace inet {

/// Writes a Middlebury .flo. Pixels with valid == 0 (or, with non_occluded_only, occluded == 1)
/// are written as unknown (1e10). `flow.occluded` may be empty unless non_occluded_only.
void writeFlo(const std::filesystem::path& path, const FlowField& flow,
              bool non_occluded_only = false);
/// Reads a Middlebury .flo: flow (0 where unknown) and valid; occluded is left empty.
FlowField readFlo(const std::filesystem::path& path);

/// Writes a KITTI 16-bit flow PNG (flow_occ style: every valid pixel; with non_occluded_only
/// the occluded ones are left out too, KITTI's flow_noc).
void writeKittiFlowPng(const std::filesystem::path& path, const FlowField& flow,
                       bool non_occluded_only = false, int png_level = kDefaultPngLevel);
/// Reads a KITTI flow PNG (16-bit, 3 channels): flow (0 where invalid) and valid; occluded empty.
FlowField readKittiFlowPng(const std::filesystem::path& path);

/// Writes a flow EXR (channels U, V; unknown = NaN) with the given lossless compression.
void writeFlowExr(const std::filesystem::path& path, const FlowField& flow,
                  ExrCompression compression = ExrCompression::Zip);
/// Reads a flow EXR: flow (0 where unknown) and valid; occluded empty. A file without U and V
/// is an InputError naming the channels it has.
FlowField readFlowExr(const std::filesystem::path& path);

}  // namespace inet
