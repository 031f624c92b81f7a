// QR codes (libqrencode; no libqrencode type in this header) for the route
// card: the link climbers scan at the wall.
#ifndef SB_PLAN_QR_H_
#define SB_PLAN_QR_H_

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"

namespace sb::plan {

// Longest text put in a QR code: a URL of this server is far shorter, and
// version 10 at level M (the largest the card prints legibly at 28 mm, 57
// modules of 0.5 mm) holds 213 bytes.
inline constexpr size_t kMaxQrBytes = 200;

// A QR code symbol: `size` x `size` modules, row-major, true = dark. The
// quiet zone (4 modules each side) is not included.
struct QrCode {
  int size = 0;
  std::vector<bool> dark;
  bool at(int x, int y) const { return dark[static_cast<size_t>(y) * size + x]; }
};

// Encodes `text` (8-bit mode, error correction level M). Errors:
// kInvalidInput for empty text or more than kMaxQrBytes; kInternal when the
// library fails. Deterministic; thread-safe.
Result<QrCode> MakeQr(std::string_view text);

// The code as an SVG element (<svg> with a white quiet zone and one path of
// dark modules, crisp edges) `width_css` wide (a CSS length such as "28mm").
// Pure.
std::string QrSvg(const QrCode& code, const std::string& width_css);

}  // namespace sb::plan

#endif  // SB_PLAN_QR_H_
