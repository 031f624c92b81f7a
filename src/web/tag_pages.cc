#include "web/tag_pages.h"

#include <cmath>
#include <optional>

#include "base/text.h"
#include "plan/colour.h"
#include "plan/qr.h"

namespace sb::web {

namespace {

std::string E(std::string_view s) { return XmlEscape(s); }

// "rgb(26,77,217)" for a swatch, "" when the colour is unknown.
std::string Css(const std::optional<plan::Rgb>& c) {
  if (!c) return "";
  auto b = [](double v) { return std::to_string(static_cast<int>(std::lround(v * 255))); };
  return "rgb(" + b(c->r) + "," + b(c->g) + "," + b(c->b) + ")";
}

}  // namespace

void LocaliseTag(std::string_view lang, plan::TagInfo* tag) {
  plan::TagInfo::Words& w = tag->words;
  w.wall = Tr(lang, "Wall: {1}");
  w.set_by = Tr(lang, "Set by {1}");
  w.to_be_set_by = Tr(lang, "To be set by {1}");
  w.set_on = Tr(lang, "Set on {1}");
  w.planned_for = Tr(lang, "Planned for {1}");
  tag->colour_label = ColourLabelIn(lang, tag->colour);
  tag->set_on = FormatDate(lang, tag->set_on);
}

std::string TagPage(const PageViewer& v, int64_t id, const plan::TagInfo& tag) {
  const std::string sid = std::to_string(id);
  const std::string colour = Css(plan::ColourSwatch(tag.colour));
  const std::string fill = colour.empty() ? "" : " style=\"background:" + colour + "\"";
  std::string b = "<article class=\"tag-sheet\" id=\"tag\">\n<div class=\"tag-card\">";
  b += "<div class=\"tag-strip\"" + fill + "></div>\n<div class=\"tag-text\">";
  if (!tag.name.empty()) b += "<h1 class=\"tag-name\">" + E(tag.name) + "</h1>\n";
  if (!tag.grade.empty()) b += "<p class=\"tag-grade\">" + E(tag.grade) + "</p>\n";
  if (!tag.colour.empty()) {
    // Issue 32: a swatch only for a colour the table knows, and its name.
    b += "<p class=\"tag-colour\">" +
         (colour.empty() ? std::string() : "<span class=\"swatch\"" + fill + "></span>") +
         E(tag.colour_label.empty() ? plan::ColourLabel(tag.colour) : tag.colour_label) +
         "</p>\n";
  }
  for (const std::string& line : plan::TagLines(tag)) {
    b += "<p class=\"tag-line\">" + E(line) + "</p>\n";
  }
  b += "</div>\n";
  if (!tag.url.empty()) {
    b += "<figure class=\"tag-qr\">";
    if (Result<plan::QrCode> qr = plan::MakeQr(tag.url); qr.ok()) {
      b += plan::QrSvg(*qr, "26.8mm");
    }
    // One line, its size from its length (the CSS divides the line's room by
    // the characters of a monospace font), never wrapped.
    b += "<figcaption class=\"tag-url\" style=\"--chars:" +
         std::to_string(std::max<size_t>(tag.url.size(), 1)) + "\">" + E(tag.url) +
         "</figcaption></figure>\n";
  }
  b += "</div>\n</article>\n";
  b += "<p class=\"actions no-print\"><button type=\"button\" id=\"print\">" +
       Tr(v, "Print the tag") + "</button> <a class=\"button\" id=\"tag-pdf\" href=\"/routes/" +
       sid + "/tag.pdf\">" + Tr(v, "PDF (A4)") +
       "</a> <a class=\"button\" id=\"tag-pdf-letter\" href=\"/routes/" + sid +
       "/tag.pdf?paper=letter\">" + Tr(v, "PDF (Letter)") + "</a> <a href=\"/routes/" + sid +
       "\">" + Tr(v, "Back to the route") + "</a></p>\n";
  return PageLayout(v, Fmt(Tr(v, "Tag: {1}"), tag.name), b, "page-tag");
}

}  // namespace sb::web
