#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "render/neural_denoise.h"

// The learned denoiser's weights file (render/neural_denoise.h): parsed, or an InputError.
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    const inet::NeuralDenoiser net = inet::parseNeuralDenoiser(bytes, "fuzz.bin");
    // what loads must be runnable: shapes match the config
    if (net.convs.size() != inet::NeuralDenoiser::shapes(net.config).size()) __builtin_trap();
    for (const inet::ConvLayer& c : net.convs)
      if (c.weight.size() != static_cast<size_t>(c.out) * c.in * c.k * c.k) __builtin_trap();
  } catch (const inet::InputError&) {
  }
  return 0;
}
