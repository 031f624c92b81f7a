// The climber's tag as a web page (issue 21): "/routes/{id}/tag" shows the
// tag of plan/tag.h at its printed size, and the browser's print gives the
// same tag as the server's PDF (GET /routes/{id}/tag.pdf). Pure.
#ifndef SB_WEB_TAG_PAGES_H_
#define SB_WEB_TAG_PAGES_H_

#include <cstdint>
#include <string>

#include "plan/tag.h"
#include "web/pages.h"

namespace sb::web {

// The tag page of route `id` (every piece of text escaped): the tag (name,
// grade, colour strip and swatch with its name, wall, setters, set date, the
// QR code of `tag.url` with the URL under it on one line), print CSS that
// puts it on one page, and links to the PDFs (A4, Letter) and the route.
std::string TagPage(const PageViewer& v, int64_t id, const plan::TagInfo& tag);

// Issue 32: `tag`'s words, colour name and set date in `lang` (web/i18n.h),
// for the page and the PDFs alike.
void LocaliseTag(std::string_view lang, plan::TagInfo* tag);

}  // namespace sb::web

#endif  // SB_WEB_TAG_PAGES_H_
