// Server-rendered pages: each asks a service and renders (web/pages.h).
#include <set>
#include <utility>

#include "app/feedback.h"
#include "app/routes.h"
#include "app/scales.h"
#include "base/text.h"
#include "crdl/route.h"
#include "plan/card.h"
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
  Result<app::RouteQuery> rq = RouteQueryOf(x.req);
  if (!rq.ok()) return PageError(x, rq.status());
  if (!rq->limit) rq->limit = x.services.options.limits.list_page_rows;
  auto slot = AdmitWork(x, ListCost(x, rq->limit));
  if (!slot) return;
  Result<app::RoutePage> page = x.services.routes.Search(x.caller.viewer, *rq);
  if (!page.ok()) return PageError(x, page.status());
  Html(x, RouteListPage(x.caller.page(), *page, *rq));
}

void PageLogin(Exchange& x) { Html(x, LoginPage(x.caller.page(), false)); }
void PageSignup(Exchange& x) { Html(x, LoginPage(x.caller.page(), true)); }
namespace {

// What the route form offers (issue 31): the gym's walls (with their grade
// scales), circuits and members when the viewer sets in `gym`; nothing
// otherwise (a personal route's form). Lookup errors leave a part empty.
RouteFormData FormDataOf(Exchange& x, std::optional<int64_t> gym) {
  RouteFormData f;
  if (!gym) return f;
  Result<app::Gym> g = x.services.gyms.Get(x.caller.viewer, *gym);
  if (!g.ok() || !app::CanSet(g->role)) return f;
  f.gym = *g;
  const app::Viewer& v = x.caller.viewer;
  if (Result<std::vector<app::Wall>> w = x.services.gyms.Walls(v, *gym); w.ok()) f.walls = *w;
  if (Result<std::vector<app::Circuit>> c = x.services.gyms.Circuits(v, *gym); c.ok()) {
    f.circuits = *c;
  }
  if (Result<std::vector<app::Member>> m = x.services.gyms.Members(v, *gym); m.ok()) {
    f.members = *m;
  }
  for (const app::Wall& w : f.walls) {
    Result<std::string> scale = x.services.scales.WallScaleName(v, w.id);
    if (scale.ok() && !scale->empty()) f.wall_scales[w.id] = *scale;
  }
  if (!f.wall_scales.empty()) {
    if (Result<std::vector<app::GymScaleView>> scales = x.services.scales.List(v, *gym);
        scales.ok()) {
      for (const app::GymScaleView& sc : *scales) {
        for (const grades::LabelSpec& l : sc.labels) f.scale_labels[sc.name].push_back(l.label);
      }
    }
  }
  return f;
}

}  // namespace

void PageNewRoute(Exchange& x) {
  RouteFormData form = FormDataOf(x, x.caller.gym);
  // Issue 31: "New route on this wall" (a wall page's link): that wall
  // chosen, when it is one of the form's gym.
  if (std::optional<int64_t> wall = ParseId(x.req.Query("wall").value_or(""))) {
    for (const app::Wall& w : form.walls) {
      if (w.id == *wall) form.wall = w.id;
    }
  }
  Html(x, EditorPage(x.caller.page(), std::nullopt, form));
}

void PageEditRoute(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "No such route.");
  if (!id.ok()) return PageError(x, id.status());
  Result<app::RouteView> r = x.services.routes.GetOwned(x.caller.viewer, *id);
  // Not logged in: the editor asks to log in first.
  if (r.status().code() == Status::Code::kUnauthenticated) {
    return Html(x, EditorPage(x.caller.page(), std::nullopt));
  }
  if (r.status().code() == Status::Code::kPermission) {
    return PageError(x, Status::Permission("Only the route's owner may edit it."));
  }
  if (!r.ok()) return PageError(x, r.status());
  auto slot =
      AdmitWork(x, r->move_count * x.services.options.render_costs.page_per_move, r->gym_id);
  if (!slot) return;
  Html(x, EditorPage(x.caller.page(), *r, FormDataOf(x, r->gym_id)));
}

void PageRoute(Exchange& x) {
  Result<int64_t> id = PathId(x.req, "No such route.");
  if (!id.ok()) return PageError(x, id.status());
  Result<app::RouteView> r = x.services.routes.Get(x.caller.viewer, *id);
  if (!r.ok()) return PageError(x, r.status());
  if (r->is_variation) {
    x.res.status = 302;
    x.res.SetHeader("Location", "/variations/" + std::to_string(*id));
    return;
  }
  // Issue 34: the page's ascent section (app::ReadCosts::AscentCost) too,
  // and its history and consensus blocks (RouteBlocksCost).
  Result<double> ascent = x.services.read_costs.AscentCost(x.caller.viewer, *id, true);
  if (!ascent.ok()) return PageError(x, ascent.status());
  Result<double> blocks = x.services.read_costs.RouteBlocksCost(x.caller.viewer, *id);
  if (!blocks.ok()) return PageError(x, blocks.status());
  auto slot = AdmitWork(
      x, r->move_count * x.services.options.render_costs.page_per_move + *ascent + *blocks,
      r->gym_id);
  if (!slot) return;
  std::vector<std::string> readings;
  if (Result<Route> parsed = ParseCrdl(r->crdl, "route"); parsed.ok()) {
    readings = app::MoveReadings(*parsed);
  }
  std::string discipline;
  if (Result<app::RouteDiscipline> d = x.services.routes.DisciplineOf(*r); d.ok()) {
    discipline = d->Describe();
  }
  Html(x, WithBlock(RoutePage(x.caller.page(), *r, x.services.routes.CanChange(x.caller.viewer, *r),
                              readings,
                              discipline),
                    GymBlock(x, *r) + ConsensusBlock(x, *r)));
}

void PageVary(Exchange& x) {
  // The chosen routes, in the order the URL names them, however old; the
  // ones the viewer may not see (or that are gone) are reported, not shown.
  std::vector<app::RouteView> chosen;
  std::vector<int64_t> missing;
  for (int64_t id : SelectedIds(x.req.Query("routes").value_or(""))) {
    Result<app::RouteView> r = x.services.routes.Get(x.caller.viewer, id);
    if (r.ok()) {
      chosen.push_back(std::move(r).value());
    } else {
      missing.push_back(id);
    }
  }
  app::RouteQuery q;
  q.text = x.req.Query("find").value_or("");
  q.limit = x.services.options.limits.picker_rows;
  Result<app::RoutePage> found = x.services.routes.Search(x.caller.viewer, q);
  if (!found.ok()) return PageError(x, found.status());
  Html(x, VaryPage(x.caller.page(), chosen, missing, *found, q.text));
}

void PageImport(Exchange& x) { Html(x, ImportPage(x.caller.page())); }

namespace {
// The variation's plan, admitted by the work budget at `base` + `per_move`
// render units per move; nullopt when refused (the reply is written).
struct AdmittedPlan {
  app::PlanView view;
  app::WorkBudget::Slot slot;
};
std::optional<AdmittedPlan> AdmittedPlanOf(Exchange& x, double base, double per_move,
                                           bool with_ascent = false) {
  Result<int64_t> id = PathId(x.req, "No such variation.");
  if (!id.ok()) {
    PageError(x, id.status());
    return std::nullopt;
  }
  // The stored move count prices the work before the plan is (re)built.
  Result<app::RouteView> r = x.services.routes.Get(x.caller.viewer, *id);
  if (!r.ok() || !r->is_variation) {
    PageError(x, r.ok() ? Status::NotFound("No such variation.") : r.status());
    return std::nullopt;
  }
  if (with_ascent) {
    // Issue 34: the page's ascent section (app::ReadCosts::AscentCost),
    // and its history and consensus blocks (RouteBlocksCost).
    Result<double> ascent = x.services.read_costs.AscentCost(x.caller.viewer, *id, true);
    if (!ascent.ok()) {
      PageError(x, ascent.status());
      return std::nullopt;
    }
    Result<double> blocks = x.services.read_costs.RouteBlocksCost(x.caller.viewer, *id);
    if (!blocks.ok()) {
      PageError(x, blocks.status());
      return std::nullopt;
    }
    base += *ascent + *blocks;
  }
  std::optional<app::WorkBudget::Slot> slot =
      AdmitWork(x, base + r->move_count * per_move, r->gym_id);
  if (!slot) return std::nullopt;
  Result<app::PlanView> p = x.services.variations.Plan(x.caller.viewer, *id);
  if (!p.ok()) {
    PageError(x, p.status());
    return std::nullopt;
  }
  return AdmittedPlan{std::move(p).value(), std::move(*slot)};
}
}  // namespace

namespace {

// What the card prints about a stored variation besides its plan.
plan::CardInfo CardInfoOf(Exchange& x, const app::RouteView& rec) {
  plan::CardInfo info;
  info.name = rec.name;
  info.grade = rec.grade;
  // The colour's name in the page's language ("gelb", "jaune"; a hex code as
  // its nearest name).
  info.colour = ColourLabelIn(x.caller.lang.empty() ? "en" : x.caller.lang, rec.colour);
  info.wall = rec.wall;
  info.setter = rec.setter.empty() ? rec.owner_name : rec.setter;
  info.date = rec.set_on.empty() ? rec.created_at.substr(0, 10) : rec.set_on;
  if (Result<Route> r = ParseCrdl(rec.crdl, "route"); r.ok()) {
    for (const HeaderLine& l : r->header) {
      if (l.key.empty() && !Trim(l.value).empty()) {
        info.notes += (info.notes.empty() ? "" : "\n") + std::string(Trim(l.value));
      }
    }
  }
  info.url = ShortLink(x, rec.id);
  // Issue 32: the card's words in the page's language.
  if (const std::string lang = x.caller.lang; !lang.empty() && lang != "en") {
    info.translate = [lang](const char* one, const char* many, long long n) {
      return many ? TrN(lang, one, many, n) : Tr(lang, one);
    };
  }
  return info;
}

plan::Paper PaperOf(Exchange& x) {
  return ToLower(x.req.Query("paper").value_or("")) == "letter" ? plan::Paper::kLetter
                                                                : plan::Paper::kA4;
}

}  // namespace

std::string ShortLink(Exchange& x, int64_t id) {
  std::string base = x.options.base_url;
  if (base.empty()) {
    std::string host = x.req.Header("Host");
    base = "http://" + (host.empty() ? std::string("localhost") : host);
  }
  while (!base.empty() && base.back() == '/') base.pop_back();
  return base + "/r/" + std::to_string(id);
}

void PagePlan(Exchange& x) {
  const app::RenderCosts& c = x.services.options.render_costs;
  std::optional<AdmittedPlan> a = AdmittedPlanOf(x, 0, c.plan_per_move, /*with_ascent=*/true);
  if (!a) return;
  const app::PlanView* p = &a->view;
  Html(x, WithBlock(PlanPage(x.caller.page(), p->record, *p->plan, p->smoothing_note,
                             CardInfoOf(x, p->record),
                             x.services.routes.CanChange(x.caller.viewer, p->record)),
                    // Issue 31: a variation accepted on a setting day is a route of
                    // the gym: its page has the "On the wall" block too.
                    GymBlock(x, p->record) + ConsensusBlock(x, p->record)));
}

void PagePlanSvg(Exchange& x) {
  const app::RenderCosts& c = x.services.options.render_costs;
  std::optional<AdmittedPlan> a = AdmittedPlanOf(x, c.card_base, c.card_per_move);
  if (!a) return;
  const app::PlanView* p = &a->view;
  Result<std::string> svg = plan::RenderCardSvg(*p->plan, CardInfoOf(x, p->record), PaperOf(x));
  if (!svg.ok()) return PageError(x, svg.status());
  x.res.SetHeader("Content-Disposition", AttachmentHeader(p->record.name, ".svg"));
  x.res.SetBody(200, *svg, "image/svg+xml");
}

void PagePlanPdf(Exchange& x) {
  const app::RenderCosts& c = x.services.options.render_costs;
  std::optional<AdmittedPlan> a = AdmittedPlanOf(x, c.card_base, c.card_per_move);
  if (!a) return;
  const app::PlanView* p = &a->view;
  plan::Paper paper = PaperOf(x);
  Result<std::string> pdf = plan::RenderCardPdf(*p->plan, CardInfoOf(x, p->record), paper);
  if (!pdf.ok()) return PageError(x, pdf.status());
  x.res.SetHeader("Content-Disposition",
                  AttachmentHeader(p->record.name,
                                   paper == plan::Paper::kLetter ? "-letter.pdf" : "-a4.pdf"));
  x.res.SetBody(200, *pdf, "application/pdf");
}

}  // namespace sb::web
