#include "render/frame.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <fmt/format.h>

#include "core/error.h"

namespace inet {
namespace {
struct PassEntry {
  Pass pass;
  const char* name;
};
constexpr PassEntry kPasses[] = {
    {Pass::Rgb, "rgb"},       {Pass::DepthZ, "depth"},    {Pass::DepthRay, "ray_depth"},
    {Pass::Normal, "normal"}, {Pass::Label, "label"},     {Pass::Instance, "instance"},
    {Pass::Albedo, "albedo"}, {Pass::Shading, "shading"}, {Pass::DepthNoisy, "depth_noisy"},
    {Pass::Flow, "flow"},     {Pass::FlowBackward, "flow_bwd"},
};
}  // namespace

std::string passName(Pass p) {
  for (const auto& e : kPasses)
    if (e.pass == p) return e.name;
  return "?";
}

std::string FlowField::toString() const {
  size_t valid_px = 0, occluded_px = 0;
  double largest = 0;
  for (size_t i = 0; i < valid.data.size(); ++i) {
    if (!valid.data[i]) continue;
    ++valid_px;
    largest = std::max(largest, std::hypot(double{flow.data[2 * i]}, double{flow.data[2 * i + 1]}));
  }
  for (uint8_t o : occluded.data) occluded_px += o != 0;
  return fmt::format("FlowField[{}x{}, {} valid, {} occluded{}, max |flow| {:.3f} px]", width(),
                     height(), valid_px, occluded_px, occluded.empty() ? " (unknown)" : "",
                     largest);
}

PassMask parsePassList(const std::string& list, const std::string& where) {
  PassMask mask = 0;
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (item.empty()) continue;
    if (item == "all") {
      mask |= kAllPasses;
      continue;
    }
    bool found = false;
    for (const auto& e : kPasses) {
      if (item == e.name) {
        mask |= static_cast<PassMask>(e.pass);
        found = true;
      }
    }
    if (!found) {
      std::vector<std::string> names;
      for (const auto& e : kPasses) names.emplace_back(e.name);
      throw InputError(
          where, "--passes",
          fmt::format("unknown pass '{}' (valid: all, {})", item, fmt::join(names, ", ")));
    }
  }
  if (mask == 0) throw InputError(where, "--passes", "no pass selected");
  return mask;
}

}  // namespace inet
