#include "render/frame.h"
#include "render/passes.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "core/error.h"

namespace inet {
// The functions of render/passes.h live here too (one library source for both headers).

std::string passName(Pass p) {
  return passInfo(p).name;
}

const ImageF& floatImage(const Frame& f, Pass p) {
  const PassInfo& info = passInfo(p);
  INET_CHECK_MSG(info.pixel == PixelType::Float,
                 fmt::format("pass '{}' is not a float image", info.name));
  return f.*info.member.f;
}

const FlowField& flowField(const Frame& f, Pass p) {
  const PassInfo& info = passInfo(p);
  INET_CHECK_MSG(info.pixel == PixelType::Flow,
                 fmt::format("pass '{}' is not a flow field", info.name));
  return f.*info.member.flow;
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
    for (const PassInfo& e : kPassTable) {
      if (item == e.name) {
        mask |= bit(e.pass);
        found = true;
      }
    }
    if (!found) {
      std::vector<std::string> names;
      for (const PassInfo& e : kPassTable) names.emplace_back(e.name);
      throw InputError(
          where, "--passes",
          fmt::format("unknown pass '{}' (valid: all, {})", item, fmt::join(names, ", ")));
    }
  }
  if (mask == 0) throw InputError(where, "--passes", "no pass selected");
  return mask;
}

}  // namespace inet
