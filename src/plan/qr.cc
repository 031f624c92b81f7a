#include "plan/qr.h"

#include <qrencode.h>

#include <memory>

namespace sb::plan {

Result<QrCode> MakeQr(std::string_view text) {
  if (text.empty()) return Status::InvalidInput("QR code: nothing to encode");
  if (text.size() > kMaxQrBytes) {
    return Status::InvalidInput("QR code: at most " + std::to_string(kMaxQrBytes) + " bytes");
  }
  const std::string data(text);
  // libqrencode keeps no global state for QRcode_encodeData; thread-safe.
  std::unique_ptr<QRcode, void (*)(QRcode*)> q(
      QRcode_encodeData(static_cast<int>(data.size()),
                        reinterpret_cast<const unsigned char*>(data.data()), 0, QR_ECLEVEL_M),
      QRcode_free);
  if (!q) return Status::Internal("QR code: libqrencode failed");
  QrCode out;
  out.size = q->width;
  out.dark.resize(static_cast<size_t>(out.size) * out.size);
  for (size_t i = 0; i < out.dark.size(); ++i) out.dark[i] = (q->data[i] & 1) != 0;
  return out;
}

std::string QrSvg(const QrCode& code, const std::string& width_css) {
  constexpr int kQuiet = 4;
  const int n = code.size + 2 * kQuiet;
  std::string path;
  for (int y = 0; y < code.size; ++y) {
    for (int x = 0; x < code.size; ++x) {
      if (!code.at(x, y)) continue;
      // Runs of dark modules on a row become one rectangle.
      int end = x;
      while (end + 1 < code.size && code.at(end + 1, y)) ++end;
      path += "M" + std::to_string(x + kQuiet) + " " + std::to_string(y + kQuiet) + "h" +
              std::to_string(end - x + 1) + "v1h-" + std::to_string(end - x + 1) + "z";
      x = end;
    }
  }
  std::string ns = std::to_string(n);
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"qr\" viewBox=\"0 0 " + ns + " " + ns +
         "\" width=\"" + width_css + "\" height=\"" + width_css +
         "\" shape-rendering=\"crispEdges\" role=\"img\" aria-label=\"QR code\">"
         "<rect width=\"" + ns + "\" height=\"" + ns + "\" fill=\"#fff\"/><path fill=\"#000\" d=\"" +
         path + "\"/></svg>";
}

}  // namespace sb::plan
