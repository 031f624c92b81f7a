// The climber's tag (issue 21, docs/web.md "The tag on the wall"): one tag
// as a page and a PDF for every route the viewer can see, and a sheet of tags
// for a list of routes. The content is plan/tag.h; app/tags.h maps a route to
// it and bounds a sheet.
#include <map>

#include "app/tags.h"
#include "base/text.h"
#include "plan/tag.h"
#include "web/handlers.h"
#include "web/i18n.h"
#include "web/tag_pages.h"

namespace sb::web {

namespace {

plan::Paper TagPaperOf(const Request& req) {
  return ToLower(req.Query("paper").value_or("")) == "letter" ? plan::Paper::kLetter
                                                              : plan::Paper::kA4;
}

// The language a tag of `r` prints in (issue 32): its gym's default language
// when the gym has one (the wall's words are the gym's, not the printer's),
// else the caller's. `seen` caches the gyms' languages over a sheet.
std::string TagLanguage(Exchange& x, const app::RouteView& r,
                        std::map<int64_t, std::string>* seen = nullptr) {
  if (!r.gym_id) return x.caller.lang;
  auto it = seen ? seen->find(*r.gym_id) : std::map<int64_t, std::string>::iterator{};
  std::string lang;
  if (seen && it != seen->end()) {
    lang = it->second;
  } else {
    if (Result<std::string> l = x.services.profiles.GymLanguage(*r.gym_id); l.ok()) lang = *l;
    if (seen) (*seen)[*r.gym_id] = lang;
  }
  return IsUiLanguage(lang) ? lang : x.caller.lang;
}

// The route of the path's id, visible to the caller, and its tag.
Result<std::pair<app::RouteView, plan::TagInfo>> TagOfPath(Exchange& x) {
  SB_ASSIGN_OR_RETURN(int64_t id, PathId(x.req, "No such route."));
  SB_ASSIGN_OR_RETURN(app::RouteView r, x.services.routes.Get(x.caller.viewer, id));
  plan::TagInfo tag = app::TagInfoOf(r, ShortLink(x, r.id));
  LocaliseTag(TagLanguage(x, r), &tag);
  return std::make_pair(std::move(r), std::move(tag));
}

void SendPdf(Exchange& x, const std::string& pdf, const std::string& name, plan::Paper paper) {
  x.res.SetHeader("Content-Disposition",
                  AttachmentHeader(name, paper == plan::Paper::kLetter ? "-letter.pdf" : "-a4.pdf"));
  x.res.SetBody(200, pdf, "application/pdf");
}

}  // namespace

void PageTag(Exchange& x) {
  auto t = TagOfPath(x);
  if (!t.ok()) return PageError(x, t.status());
  x.res.SetHeader("Cache-Control", "no-store");
  x.res.SetBody(200, TagPage(x.caller.page(), t->first.id, t->second), "text/html; charset=utf-8");
}

void PageTagPdf(Exchange& x) {
  auto t = TagOfPath(x);
  if (!t.ok()) return PageError(x, t.status());
  const app::RenderCosts& c = x.services.options.render_costs;
  std::optional<app::WorkBudget::Slot> slot = AdmitWork(x, c.tag_base + c.tag_each);
  if (!slot) return;
  const plan::Paper paper = TagPaperOf(x.req);
  Result<std::string> pdf = plan::RenderTagPdf(t->second, paper);
  if (!pdf.ok()) return PageError(x, pdf.status());
  SendPdf(x, *pdf, "tag-" + t->first.name, paper);
}

void GetTagSheetPdf(Exchange& x) {
  std::vector<int64_t> ids;
  const std::string list = x.req.Query("ids").value_or("");  // outlives the views of Split
  for (std::string_view part : Split(list, ',')) {
    if (Trim(part).empty()) continue;
    std::optional<int64_t> id = ParseId(std::string(Trim(part)));
    if (!id) {
      return PageError(x, Status::InvalidInput("ids: \"" + std::string(part) +
                                               "\" is not a route id (ids=1,2,3)"));
    }
    ids.push_back(*id);
  }
  Result<std::vector<app::RouteView>> routes =
      app::TagSheetRoutes(x.services.routes, x.caller.viewer, ids, x.services.options.limits);
  if (!routes.ok()) return PageError(x, routes.status());
  const app::RenderCosts& c = x.services.options.render_costs;
  std::optional<app::WorkBudget::Slot> slot =
      AdmitWork(x, c.tag_base + c.tag_each * static_cast<double>(routes->size()));
  if (!slot) return;
  std::vector<plan::TagInfo> tags;
  tags.reserve(routes->size());
  std::map<int64_t, std::string> gym_langs;
  for (const app::RouteView& r : *routes) {
    tags.push_back(app::TagInfoOf(r, ShortLink(x, r.id)));
    LocaliseTag(TagLanguage(x, r, &gym_langs), &tags.back());
  }
  const plan::Paper paper = TagPaperOf(x.req);
  Result<std::string> pdf = plan::RenderTagSheetPdf(tags, paper);
  if (!pdf.ok()) return PageError(x, pdf.status());
  SendPdf(x, *pdf, "tags", paper);
}

void GetGymTagSheetPdf(Exchange& x) {
  std::optional<int64_t> gym = ParseId(x.req.PathParam("id"));
  if (!gym) return ApiError(x, Status::NotFound("no such gym"));
  Result<std::vector<app::RouteView>> routes = app::GymTagSheetRoutes(
      x.services.routes, x.caller.viewer, *gym, x.req.Query("wall").value_or(""),
      x.req.Query("state").value_or(""), x.services.options.limits);
  if (!routes.ok()) return ApiError(x, routes.status());
  if (routes->empty()) {
    return ApiError(x, Status::NotFound("no routes to tag (wall and state filters)"));
  }
  const app::RenderCosts& c = x.services.options.render_costs;
  std::optional<app::WorkBudget::Slot> slot =
      AdmitWork(x, c.tag_base + c.tag_each * static_cast<double>(routes->size()), *gym);
  if (!slot) return;
  std::vector<plan::TagInfo> tags;
  tags.reserve(routes->size());
  std::map<int64_t, std::string> gym_langs;
  for (const app::RouteView& r : *routes) {
    tags.push_back(app::TagInfoOf(r, ShortLink(x, r.id)));
    LocaliseTag(TagLanguage(x, r, &gym_langs), &tags.back());
  }
  const plan::Paper paper = TagPaperOf(x.req);
  Result<std::string> pdf = plan::RenderTagSheetPdf(tags, paper);
  if (!pdf.ok()) return ApiError(x, pdf.status());
  SendPdf(x, *pdf, "tags-gym-" + std::to_string(*gym), paper);
}

}  // namespace sb::web
