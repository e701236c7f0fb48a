#pragma once
// Private to src/eval's .cpp files: our images as OpenCV matrices. OpenCV types stay out of the
// public headers (inet_eval links OpenCV privately), so only implementation files include this.
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "core/image.h"

namespace inet::cvimage {

/// 8-bit grey of an sRGB colour image (or a copy of a grey one), with OpenCV's RGB2GRAY weights
/// on the stored codes: what ORB-SLAM and OpenCV's own RGB-D samples feed their trackers.
inline cv::Mat grey(const ImageU8& img) {
  INET_CHECK(img.channels == 1 || img.channels == 3);
  // the wrapper does not own the data; cvtColor and clone copy it out
  const cv::Mat view(img.height, img.width, img.channels == 3 ? CV_8UC3 : CV_8UC1,
                     const_cast<uint8_t*>(img.data.data()));
  if (img.channels == 1) return view.clone();
  cv::Mat out;
  cv::cvtColor(view, out, cv::COLOR_RGB2GRAY);
  return out;
}

/// A 1-channel float image (metres) as CV_32FC1; `none` replaces 0 (no depth).
inline cv::Mat depth(const ImageF& img, float none) {
  INET_CHECK(img.channels == 1);
  cv::Mat out(img.height, img.width, CV_32FC1);
  for (int y = 0; y < img.height; ++y) {
    float* row = out.ptr<float>(y);
    for (int x = 0; x < img.width; ++x) {
      const float d = img.at(x, y);
      row[x] = d > 0 ? d : none;
    }
  }
  return out;
}

}  // namespace inet::cvimage
