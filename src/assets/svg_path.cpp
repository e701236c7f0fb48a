#include "assets/svg_path.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>

#include "core/error.h"

namespace inet {
namespace {

using Eigen::Vector2d;

constexpr size_t kNoOffset = static_cast<size_t>(-1);

// SVG 1.1 wsp; Batik accepts exactly these four (no form feed).
bool isWsp(int c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}
bool isDigit(int c) {
  return c >= '0' && c <= '9';
}
bool startsNumber(int c) {
  return isDigit(c) || c == '+' || c == '-' || c == '.';
}
bool isFinite(const Vector2d& p) {
  return std::isfinite(p.x()) && std::isfinite(p.y());
}

// Messages stay on one line whatever bytes the path holds.
std::string describe(int c) {
  if (c < 0) return "the end of the path";
  if (c >= 0x21 && c <= 0x7e) return fmt::format("'{}'", static_cast<char>(c));
  return fmt::format("byte 0x{:02x}", c);
}

class PathParser {
 public:
  PathParser(std::string_view d, double tolerance, const std::string& file,
             const std::string& field)
      : d_(d), tol_(tolerance), merge_dist_(1e-6 * tolerance), file_(file), field_(field) {}

  std::vector<Outline2d> run() {
    skipWsp();
    if (peek() != 'M' && peek() != 'm')
      fail(pos_,
           fmt::format("a path must start with a moveto (M or m), found {}", describe(peek())));
    for (skipWsp(); pos_ < d_.size(); skipWsp()) command();
    finishSubpath();
    if (outlines_.empty()) fail(d_.size(), "the path draws no outline (it only moves)");
    return std::move(outlines_);
  }

 private:
  [[noreturn]] void fail(size_t offset, const std::string& problem) const {
    throw InputError(file_, field_, fmt::format("offset {}: {}", offset, problem));
  }

  int peek() const { return pos_ < d_.size() ? static_cast<unsigned char>(d_[pos_]) : -1; }
  void skipWsp() {
    while (isWsp(peek())) ++pos_;
  }
  // comma-wsp between arguments: whitespace, at most one comma, whitespace. Returns whether
  // a comma was seen, because a comma promises another number.
  bool skipCommaWsp() {
    skipWsp();
    if (peek() != ',') return false;
    ++pos_;
    skipWsp();
    return true;
  }

  double number() {
    const size_t start = pos_;
    size_t i = pos_;
    auto at = [&](size_t k) { return k < d_.size() ? static_cast<unsigned char>(d_[k]) : -1; };
    if (at(i) == '+' || at(i) == '-') ++i;
    size_t digits = 0;
    for (; isDigit(at(i)); ++i) ++digits;
    if (at(i) == '.')  // a second '.' starts the next number ("1.5.5" = 1.5, .5)
      for (++i; isDigit(at(i)); ++i) ++digits;
    if (digits == 0)
      fail(start, fmt::format("expected a number in the arguments of '{}' from offset {}, found {}",
                              cmd_, cmd_pos_, describe(at(start))));
    if (at(i) == 'e' || at(i) == 'E') {
      size_t j = i + 1;
      if (at(j) == '+' || at(j) == '-') ++j;
      if (!isDigit(at(j))) fail(i, "malformed exponent in a number");
      while (isDigit(at(j))) ++j;
      i = j;
    }
    pos_ = i;
    // from_chars is locale-independent but takes no '+'.
    const char* first = d_.data() + start + (d_[start] == '+' ? 1 : 0);
    double v = 0;
    auto [end, ec] = std::from_chars(first, d_.data() + i, v);
    if (ec != std::errc() || end != d_.data() + i || !std::isfinite(v))
      fail(start, fmt::format("number '{}' is out of the range of double precision",
                              d_.substr(start, std::min<size_t>(i - start, 40))));
    return v;
  }

  Vector2d pair() {
    const double x = number();
    skipCommaWsp();
    return {x, number()};
  }

  bool flag() {
    const int c = peek();
    if (c != '0' && c != '1')
      fail(pos_, fmt::format("expected an arc flag (0 or 1) in the arguments of '{}' from offset "
                             "{}, found {}",
                             cmd_, cmd_pos_, describe(c)));
    ++pos_;
    skipCommaWsp();
    return c == '1';
  }

  // Relative coordinates are offsets from the current point of the command's start.
  Vector2d absolute(const Vector2d& p, bool relative) const {
    Vector2d a = relative ? Vector2d(pt_ + p) : p;
    if (!isFinite(a)) fail(cmd_pos_, "a coordinate overflows double precision");
    return a;
  }

  void command() {
    cmd_pos_ = pos_;
    cmd_ = d_[pos_];
    if (std::string_view("MmLlHhVvCcSsQqTtAaZz").find(cmd_) == std::string_view::npos) {
      // Every other command swallows the numbers that follow it, so a stray one follows Z.
      if (startsNumber(peek()))
        fail(pos_, fmt::format("unexpected number {}; Z takes no arguments", describe(peek())));
      fail(pos_, fmt::format("unknown path command {}", describe(peek())));
    }
    const bool rel = cmd_ >= 'a';
    const char upper = rel ? static_cast<char>(cmd_ - 'a' + 'A') : cmd_;
    ++pos_;
    skipWsp();
    if (upper == 'Z') {
      closeSubpath();
      prev_ = 'Z';
      return;
    }
    char kind = upper;
    for (;;) {
      segment(kind, rel);
      // Pairs after a moveto are linetos (relative after m).
      if (kind == 'M') kind = 'L';
      const bool comma = skipCommaWsp();
      if (!startsNumber(peek())) {
        if (comma)
          fail(pos_, fmt::format("expected a number after ',', found {}", describe(peek())));
        return;
      }
      cmd_pos_ = pos_;  // errors in a repeated group point at that group
    }
  }

  void segment(char kind, bool rel) {
    switch (kind) {
      case 'M':
        moveTo(absolute(pair(), rel));
        break;
      case 'L':
        lineTo(absolute(pair(), rel));
        break;
      case 'H':
        lineTo(absolute({number(), rel ? 0.0 : pt_.y()}, rel));
        break;
      case 'V':
        lineTo(absolute({rel ? 0.0 : pt_.x(), number()}, rel));
        break;
      case 'C': {
        const Vector2d c1 = absolute(pair(), rel);
        skipCommaWsp();
        const Vector2d c2 = absolute(pair(), rel);
        skipCommaWsp();
        cubicTo(c1, c2, absolute(pair(), rel));
        break;
      }
      case 'S': {
        const Vector2d c2 = absolute(pair(), rel);
        skipCommaWsp();
        cubicTo(reflectedControl('C', 'S'), c2, absolute(pair(), rel));
        break;
      }
      case 'Q': {
        const Vector2d c = absolute(pair(), rel);
        skipCommaWsp();
        quadTo(c, absolute(pair(), rel));
        break;
      }
      case 'T':
        quadTo(reflectedControl('Q', 'T'), absolute(pair(), rel));
        break;
      case 'A': {
        const double rx = number();
        skipCommaWsp();
        const double ry = number();
        skipCommaWsp();
        const double angle_deg = number();
        skipCommaWsp();
        const bool large_arc = flag();
        const bool sweep = flag();
        arcTo(rx, ry, angle_deg, large_arc, sweep, absolute(pair(), rel));
        break;
      }
    }
    prev_ = kind;
  }

  // S and T mirror the previous curve's last control point through the current point, but
  // only when the previous command was of the same family (SVG 1.1 section 8.3.6 and 8.3.7).
  Vector2d reflectedControl(char a, char b) const {
    if (prev_ != a && prev_ != b) return pt_;
    const Vector2d c = 2.0 * pt_ - ctrl_;
    if (!isFinite(c)) fail(cmd_pos_, "a control point overflows double precision");
    return c;
  }

  void moveTo(const Vector2d& p) {
    finishSubpath();
    start_ = pt_ = p;
    cur_.assign(1, p);
    subpath_pos_ = cmd_pos_;
  }

  void markDrawn() {
    if (drawn_) return;
    drawn_ = true;
    if (subpath_pos_ == kNoOffset) subpath_pos_ = cmd_pos_;
  }

  void emit(const Vector2d& p) {
    if (!isFinite(p)) fail(cmd_pos_, "a coordinate overflows double precision");
    if (!cur_.empty() && (p - cur_.back()).norm() <= merge_dist_) return;
    if (committed_ + cur_.size() >= kMaxSvgPathVertices) tooManyVertices();
    cur_.push_back(p);
  }

  [[noreturn]] void tooManyVertices() const {
    fail(cmd_pos_, fmt::format("the path needs more than {} vertices at tolerance {}",
                               kMaxSvgPathVertices, tol_));
  }

  // Number of chords for a curve whose second derivative is bounded by `max_d2` over a
  // parameter range of length `range`: linear interpolation with step h is off by at most
  // h^2/8 * max_d2. Refuses counts beyond the vertex budget before allocating anything.
  size_t chordCount(double range, double max_d2) const {
    const double n = std::ceil(range * std::sqrt(max_d2 / (8.0 * tol_)));
    if (!std::isfinite(max_d2) || std::isnan(n))
      fail(cmd_pos_, "a curve's coordinates overflow double precision");
    const double budget = static_cast<double>(kMaxSvgPathVertices - committed_ - cur_.size());
    if (!(n <= budget)) tooManyVertices();
    return std::max<size_t>(1, static_cast<size_t>(n));
  }

  void lineTo(const Vector2d& p) {
    markDrawn();
    emit(p);
    pt_ = p;
  }

  void cubicTo(const Vector2d& c1, const Vector2d& c2, const Vector2d& p) {
    markDrawn();
    const Vector2d p0 = pt_;
    // B''(t) = 6((1-t)(P0-2P1+P2) + t(P1-2P2+P3)) is a convex mix, so its norm is at most
    // 6 * the larger of the two second differences.
    const double d2 = 6.0 * std::max((p0 - 2.0 * c1 + c2).norm(), (c1 - 2.0 * c2 + p).norm());
    const size_t n = chordCount(1.0, d2);
    for (size_t i = 1; i < n; ++i) {
      const double t = static_cast<double>(i) / static_cast<double>(n), s = 1.0 - t;
      emit(s * s * s * p0 + 3.0 * s * s * t * c1 + 3.0 * s * t * t * c2 + t * t * t * p);
    }
    emit(p);  // the exact end point, so relative commands that follow do not drift
    ctrl_ = c2;
    pt_ = p;
  }

  void quadTo(const Vector2d& c, const Vector2d& p) {
    markDrawn();
    const Vector2d p0 = pt_;
    const size_t n = chordCount(1.0, 2.0 * (p0 - 2.0 * c + p).norm());  // B'' is constant
    for (size_t i = 1; i < n; ++i) {
      const double t = static_cast<double>(i) / static_cast<double>(n), s = 1.0 - t;
      emit(s * s * p0 + 2.0 * s * t * c + t * t * p);
    }
    emit(p);
    ctrl_ = c;
    pt_ = p;
  }

  // SVG 1.1 F.6.5, computed in the "unit circle" frame u = R(-phi)(p0 - p)/2 scaled by 1/r so
  // that no step squares a radius: huge or tiny radii neither overflow nor lose the centre.
  void arcTo(double rx, double ry, double angle_deg, bool large_arc, bool sweep,
             const Vector2d& p) {
    markDrawn();
    const Vector2d p0 = pt_;
    pt_ = p;
    if (p == p0) return;  // F.6.2: an arc to its own start point is omitted
    rx = std::abs(rx);
    ry = std::abs(ry);
    if (rx == 0 || ry == 0) {  // F.6.6: zero radius is a straight line
      emit(p);
      return;
    }
    const double phi = std::fmod(angle_deg, 360.0) * std::numbers::pi / 180.0;
    const double cs = std::cos(phi), sn = std::sin(phi);
    const Vector2d h = 0.5 * p0 - 0.5 * p;
    const Vector2d q(cs * h.x() + sn * h.y(), -sn * h.x() + cs * h.y());
    const Vector2d u(q.x() / rx, q.y() / ry);  // start point if the radii fit, else outside
    const double un = std::hypot(u.x(), u.y());
    if (!(un > 0) || !std::isfinite(un))
      fail(cmd_pos_, "the arc's radii are out of range for its end points");
    const Vector2d dir = u / un;
    // F.6.6 step 3: radii too small to reach are scaled up until the chord is a diameter.
    const double ul = std::min(un, 1.0);  // |u| after that scaling
    if (un > 1) {
      rx *= un;
      ry *= un;
    }
    // Centre cu on the chord's perpendicular bisector at signed distance s (F.6.5.2), start
    // point a and end point b = -ul * dir - cu, all on the unit circle.
    const double s = std::sqrt((1.0 - ul) * (1.0 + ul)) * (large_arc != sweep ? 1.0 : -1.0);
    const Vector2d cu(s * dir.y(), -s * dir.x());
    const Vector2d mid = 0.5 * p0 + 0.5 * p;
    const Vector2d centre(mid.x() + cs * rx * cu.x() - sn * ry * cu.y(),
                          mid.y() + sn * rx * cu.x() + cs * ry * cu.y());
    const Vector2d a = ul * dir - cu;
    const double theta1 = std::atan2(a.y(), a.x());
    // As cu is perpendicular to dir: cross(a, b) = 2 s ul and dot(a, b) = 1 - 2 ul^2 exactly,
    // which keeps the tiny sweep of a huge radius accurate where a.x*b.y - a.y*b.x would not.
    double dtheta = std::atan2(2.0 * s * ul, 1.0 - 2.0 * ul * ul);
    if (!sweep && dtheta > 0) dtheta -= 2.0 * std::numbers::pi;
    if (sweep && dtheta < 0) dtheta += 2.0 * std::numbers::pi;
    if (!isFinite(centre) || !std::isfinite(rx) || !std::isfinite(ry))
      fail(cmd_pos_, "the arc's geometry overflows double precision");
    // |E''(theta)| = |R diag(rx, ry) (cos, sin)| <= max(rx, ry).
    const size_t n = chordCount(std::abs(dtheta), std::max(rx, ry));
    for (size_t i = 1; i < n; ++i) {
      const double t = theta1 + dtheta * static_cast<double>(i) / static_cast<double>(n);
      const double ex = rx * std::cos(t), ey = ry * std::sin(t);
      emit({centre.x() + cs * ex - sn * ey, centre.y() + sn * ex + cs * ey});
    }
    emit(p);
  }

  void closeSubpath() {
    if (drawn_) {
      finishSubpath();
      // A drawing command after Z starts a new subpath at the same initial point.
      cur_.assign(1, start_);
      subpath_pos_ = kNoOffset;
    }
    pt_ = start_;
  }

  void finishSubpath() {
    if (!drawn_) {
      cur_.clear();
      return;
    }
    drawn_ = false;
    while (cur_.size() > 1 && (cur_.back() - cur_.front()).norm() <= merge_dist_) cur_.pop_back();
    Outline2d sorted = cur_;
    auto less = [](const Vector2d& a, const Vector2d& b) {
      return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
    };
    std::sort(sorted.begin(), sorted.end(), less);
    const size_t distinct = std::unique(sorted.begin(), sorted.end()) - sorted.begin();
    if (distinct < 3)
      fail(subpath_pos_, fmt::format("the subpath that starts here has only {} distinct "
                                     "vertices; an outline needs at least 3",
                                     distinct));
    committed_ += cur_.size();
    outlines_.push_back(std::move(cur_));
    cur_.clear();
  }

  std::string_view d_;
  size_t pos_ = 0;
  double tol_;
  double merge_dist_;  // consecutive vertices this close are one (norm, not squared: no overflow)
  const std::string& file_;
  const std::string& field_;

  std::vector<Outline2d> outlines_;
  size_t committed_ = 0;  // vertices in outlines_
  Outline2d cur_;         // the open subpath
  bool drawn_ = false;    // whether the open subpath has a drawing command
  size_t subpath_pos_ = 0;

  char cmd_ = 0;          // the command letter being parsed, for messages
  size_t cmd_pos_ = 0;    // where it (or its current argument group) starts
  char prev_ = 0;         // upper-case kind of the previous segment, for S and T
  Vector2d pt_{0, 0};     // current point
  Vector2d start_{0, 0};  // initial point of the current subpath
  Vector2d ctrl_{0, 0};   // last control point of the previous curve
};

}  // namespace

std::vector<Outline2d> parseSvgPath(std::string_view d, double tolerance,
                                    const std::string& where_file, const std::string& where_field) {
  INET_CHECK_MSG(std::isfinite(tolerance) && tolerance > 0,
                 fmt::format("parseSvgPath: tolerance {} must be finite and > 0", tolerance));
  return PathParser(d, tolerance, where_file, where_field).run();
}

double outlineArea(const Outline2d& o) {
  double twice = 0;
  for (size_t i = 0, n = o.size(); i < n; ++i) {
    const Vector2d& a = o[i];
    const Vector2d& b = o[(i + 1) % n];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * twice;
}

void orientCounterClockwiseYUp(Outline2d& o) {
  if (outlineArea(o) < 0) std::reverse(o.begin(), o.end());
}

}  // namespace inet
