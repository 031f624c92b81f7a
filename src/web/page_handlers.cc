// Server-rendered pages: each asks a service and renders (web/pages.h).
#include <set>

#include "app/feedback.h"
#include "app/routes.h"
#include "base/text.h"
#include "crdl/route.h"
#include "plan/pdf.h"
#include "web/climber_handlers.h"
#include "web/handlers.h"

namespace sb::web {

namespace {

void Html(Exchange& x, const std::string& html) {
  x.res.SetHeader("Cache-Control", "no-store");
  x.res.SetBody(200, html, "text/html; charset=utf-8");
}

// `page` with `block` (the climbers' consensus, climber_handlers.h) at the
// end of its <main>.
std::string WithBlock(std::string page, const std::string& block) {
  size_t at = page.rfind("</main>");
  if (at != std::string::npos) page.insert(at, block);
  return page;
}

// "1,2,x" -> the ids that parse (the vary page's preselection).
std::vector<int64_t> SelectedIds(const std::string& s) {
  std::vector<int64_t> out;
  for (std::string_view part : Split(s, ',')) {
    if (std::optional<int64_t> id = ParseId(std::string(Trim(part)))) out.push_back(*id);
  }
  return out;
}

}  // namespace

void PageIndex(Exchange& x) {
  ListQuery q{x.req.Query("q").value_or(""), x.req.Query("grade").value_or(""),
              x.req.Query("setter").value_or("")};
  app::RouteQuery rq;
  rq.text = q.q;
  rq.grade = q.grade;
  rq.setter = q.setter;
  Result<std::vector<store::RouteRecord>> rs = x.services.routes.List(x.caller.viewer, rq);
  if (!rs.ok()) return PageError(x, rs.status());
  Html(x, RouteListPage(x.caller.page(), *rs, q));
}

void PageLogin(Exchange& x) { Html(x, LoginPage(x.caller.page(), false)); }
void PageSignup(Exchange& x) { Html(x, LoginPage(x.caller.page(), true)); }
void PageNewRoute(Exchange& x) { Html(x, EditorPage(x.caller.page(), std::nullopt)); }

void PageEditRoute(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "No such route.");
  if (!id.ok()) return PageError(x, id.status());
  Result<store::RouteRecord> r = x.services.routes.GetOwned(x.caller.viewer, *id);
  // Not logged in: the editor asks to log in first.
  if (r.status().code() == Status::Code::kUnauthenticated) {
    return Html(x, EditorPage(x.caller.page(), std::nullopt));
  }
  if (r.status().code() == Status::Code::kPermission) {
    return PageError(x, Status::Permission("Only the route's owner may edit it."));
  }
  if (!r.ok()) return PageError(x, r.status());
  Html(x, EditorPage(x.caller.page(), *r));
}

void PageRoute(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "No such route.");
  if (!id.ok()) return PageError(x, id.status());
  Result<store::RouteRecord> r = x.services.routes.Get(x.caller.viewer, *id);
  if (!r.ok()) return PageError(x, r.status());
  if (r->is_variation) {
    x.res.status = 302;
    x.res.SetHeader("Location", "/variations/" + std::to_string(*id));
    return;
  }
  std::vector<std::string> readings;
  if (Result<Route> parsed = ParseCrdl(r->crdl, "route"); parsed.ok()) {
    readings = app::MoveReadings(*parsed);
  }
  Html(x, WithBlock(RoutePage(x.caller.page(), *r, app::IsOwner(*r, x.caller.viewer), readings),
                    ConsensusBlock(x, *r)));
}

void PageVary(Exchange& x) {
  Result<std::vector<store::RouteRecord>> rs = x.services.routes.List(x.caller.viewer, {});
  if (!rs.ok()) return PageError(x, rs.status());
  std::vector<int64_t> sel = SelectedIds(x.req.Query("routes").value_or(""));
  // Selected routes first, in the order asked, then the rest.
  std::vector<store::RouteRecord> ordered;
  for (int64_t id : sel) {
    for (const store::RouteRecord& r : *rs) {
      if (r.id == id) ordered.push_back(r);
    }
  }
  std::set<int64_t> s(sel.begin(), sel.end());
  for (const store::RouteRecord& r : *rs) {
    if (!s.count(r.id)) ordered.push_back(r);
  }
  Html(x, VaryPage(x.caller.page(), ordered, sel));
}

void PageImport(Exchange& x) { Html(x, ImportPage(x.caller.page())); }

namespace {
Result<app::PlanView> PlanOf(Exchange& x) {
  SB_ASSIGN_OR_RETURN(int64_t id, PathId(x.req, "No such variation."));
  return x.services.variations.Plan(x.caller.viewer, id);
}
}  // namespace

void PagePlan(Exchange& x) {
  Result<app::PlanView> p = PlanOf(x);
  if (!p.ok()) return PageError(x, p.status());
  Html(x, WithBlock(PlanPage(x.caller.page(), p->record, *p->plan, p->smoothing_note),
                    ConsensusBlock(x, p->record)));
}

void PagePlanSvg(Exchange& x) {
  Result<app::PlanView> p = PlanOf(x);
  if (!p.ok()) return PageError(x, p.status());
  x.res.SetBody(200, plan::RenderTrajectorySvg(*p->plan), "image/svg+xml");
}

void PagePlanPdf(Exchange& x) {
  Result<app::PlanView> p = PlanOf(x);
  if (!p.ok()) return PageError(x, p.status());
  plan::Paper paper = ToLower(x.req.Query("paper").value_or("")) == "letter" ? plan::Paper::kLetter
                                                                           : plan::Paper::kA4;
  Result<std::string> pdf = plan::RenderPdf(*p->plan, p->record.name, paper);
  if (!pdf.ok()) return PageError(x, pdf.status());
  x.res.SetHeader("Content-Disposition",
                  "inline; filename=\"variation-" + std::to_string(p->record.id) + ".pdf\"");
  x.res.SetBody(200, *pdf, "application/pdf");
}

}  // namespace sb::web
