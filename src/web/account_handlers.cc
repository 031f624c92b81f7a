// Issue 32: the account (GET/PUT/DELETE /api/account, one's own data as
// files) and its page /account. docs/web.md ("The account page").
#include "base/text.h"
#include "web/handlers.h"
#include "web/pages.h"

namespace sb::web {

using nlohmann::json;

namespace {

std::string E(std::string_view s) { return XmlEscape(s); }

json ProfileJson(const app::Profile& p) {
  return json{{"id", p.user_id},
              {"username", p.username},
              {"display_name", p.display_name},
              {"shown_name", p.shown()},
              {"language", p.language}};
}

// An optional string field: absent -> nullopt; null -> "".
Result<std::optional<std::string>> OptionalString(const json& body, const char* field) {
  if (!body.contains(field)) return std::optional<std::string>();
  if (body[field].is_null()) return std::optional<std::string>(std::string());
  SB_ASSIGN_OR_RETURN(std::string v, StringField(body, field));
  return std::optional<std::string>(std::string(Trim(v)));
}

}  // namespace

void GetAccount(Exchange& x) {
  Result<app::Profile> p = x.services.profiles.Get(x.caller.viewer);
  if (!p.ok()) return ApiError(x, p.status());
  ReplyJson(x.res, 200, ProfileJson(*p));
}

void PutAccount(Exchange& x) {
  if (!x.caller.viewer.logged_in()) return ApiError(x, Status::Unauthenticated("log in first"));
  Result<json> body = BodyObject(x.req);
  if (!body.ok()) return ApiError(x, body.status());
  app::AccountEdit edit;
  for (auto [field, out] : {std::pair<const char*, std::optional<std::string>*>{
                                "display_name", &edit.display_name},
                            {"language", &edit.language}}) {
    Result<std::optional<std::string>> v = OptionalString(*body, field);
    if (!v.ok()) return ApiError(x, v.status());
    *out = *v;
  }
  if (body->contains("password")) {
    Result<std::string> pw = StringField(*body, "password");
    if (!pw.ok()) return ApiError(x, pw.status());
    edit.password = *pw;
    Result<std::string> cur = StringField(*body, "current_password");
    if (!cur.ok()) return ApiError(x, cur.status());
    edit.current_password = *cur;
  }
  if (Status s = x.services.profiles.Update(x.caller.viewer, edit, x.caller.session_token);
      !s.ok()) {
    return ApiError(x, s);
  }
  Result<app::Profile> p = x.services.profiles.Get(x.caller.viewer);
  if (!p.ok()) return ApiError(x, p.status());
  ReplyJson(x.res, 200, ProfileJson(*p));
}

void DeleteAccount(Exchange& x) {
  if (!x.caller.viewer.logged_in()) return ApiError(x, Status::Unauthenticated("log in first"));
  Result<json> body = BodyObject(x.req);
  if (!body.ok()) return ApiError(x, body.status());
  Result<std::string> pw = StringField(*body, "password");
  if (!pw.ok()) return ApiError(x, pw.status());
  if (Status s = x.services.profiles.Delete(x.caller.viewer, *pw); !s.ok()) return ApiError(x, s);
  x.res.SetHeader("Set-Cookie", std::string(kSessionCookie) +
                                    "=; Path=/; HttpOnly; SameSite=Lax; Max-Age=0");
  x.res.status = 204;
}

void GetAccountTicksCsv(Exchange& x) {
  // Issue 34: the account's logbook is read; its cost from the counts first.
  Result<double> cost = x.services.read_costs.LogbookCost(x.caller.viewer, "");
  if (!cost.ok()) return ApiError(x, cost.status());
  auto slot = AdmitWork(x, *cost);
  if (!slot) return;
  Result<std::string> csv = x.services.profiles.TicksCsv(x.caller.viewer, x.services.logbook);
  if (!csv.ok()) return ApiError(x, csv.status());
  x.res.SetHeader("Content-Disposition", "attachment; filename=\"ticks.csv\"");
  x.res.SetBody(200, *csv, "text/csv; charset=utf-8");
}

void GetAccountRoutesTar(Exchange& x) {
  // Issue 34: every route of the account is read whole; counted first.
  std::optional<app::WorkBudget::Slot> slot;
  if (x.caller.viewer.logged_in()) {
    app::RouteQuery q;
    q.mine = true;
    q.limit = 1;
    Result<app::RoutePage> count = x.services.routes.Search(x.caller.viewer, q);
    if (!count.ok()) return ApiError(x, count.status());
    slot = AdmitWork(x, count->total * x.services.options.render_costs.export_per_route);
    if (!slot) return;
  }
  Result<std::string> tar = x.services.profiles.RoutesTar(x.caller.viewer);
  if (!tar.ok()) return ApiError(x, tar.status());
  x.res.SetHeader("Content-Disposition", "attachment; filename=\"routes.tar\"");
  x.res.SetBody(200, *tar, "application/x-tar");
}

void PageAccount(Exchange& x) {
  Result<app::Profile> p = x.services.profiles.Get(x.caller.viewer);
  if (!p.ok()) return PageError(x, p.status());
  const PageViewer v = x.caller.page();
  auto lang = [&](const char* code, const std::string& name) {
    return std::string("<option value=\"") + code + "\"" +
           (p->language == code ? " selected" : "") + ">" + name + "</option>";
  };
  auto form = [](const std::string& id, const std::string& api, const std::string& fields,
                 const std::string& submit, const std::string& next = "") {
    return "<form class=\"gym-form\" id=\"" + id + "\" data-api=\"" + api + "\"" +
           (next.empty() ? "" : " data-next=\"" + next + "\"") + ">" + fields +
           "<button type=\"submit\">" + submit +
           "</button><p class=\"msg\" role=\"status\"></p></form>\n";
  };
  std::string b = "<h1>" + Tr(v, "Your account") + "</h1>\n";
  b += "<p>" +
       Fmt(Tr(v, "Log-in name: {1} (it stays as it is)."),
           "<strong id=\"account-username\">" + E(p->username) + "</strong>") +
       "</p>\n";
  b += "<h2>" + Tr(v, "Name and language") + "</h2>\n";
  // The page reloads after a save: a new language shows at once.
  b += form("account-profile", "PUT /api/account",
            "<label>" + Tr(v, "Display name") +
                " <input name=\"display_name\" id=\"display-name\" maxlength=\"80\" value=\"" +
                E(p->display_name) + "\" placeholder=\"" + E(p->username) + "\"></label> <label>" +
                Tr(v, "Language") + " <select name=\"language\" id=\"language\">" +
                lang("", Tr(v, "the browser's")) + lang("en", "English") +  // i18n: name
                lang("de", "Deutsch") + lang("fr", "Français") +          // i18n: name
                "</select></label> ",
            Tr(v, "Save"), "/account");
  b += "<h2>" + Tr(v, "Password") + "</h2>\n<p>" +
       Tr(v, "Changing it ends your other sessions (other browsers and phones log in again).") +
       "</p>\n";
  b += form("account-password", "PUT /api/account",
            "<label>" + Tr(v, "Current password") +
                " <input type=\"password\" name=\"current_password\" id=\"current-password\" "
                "autocomplete=\"current-password\" required></label> <label>" +
                Tr(v, "New password") +
                " <input type=\"password\" name=\"password\" id=\"new-password\" "
                "autocomplete=\"new-password\" minlength=\"8\" required></label> ",
            Tr(v, "Change password"));
  b += "<h2>" + Tr(v, "Your data") +
       "</h2>\n<ul id=\"account-data\"><li><a href=\"/api/account/ticks.csv\" "
       "id=\"download-ticks\" download>" +
       Tr(v, "Logbook and ticks (CSV)") +
       "</a></li><li><a href=\"/api/account/routes.tar\" id=\"download-routes\" download>" +
       Tr(v, "Your routes (CRDL files, tar)") + "</a></li></ul>\n";
  b += "<h2>" + Tr(v, "Delete the account") + "</h2>\n<p>" +
       Tr(v, "Your routes stay in their gyms without your name; your ticks stay, anonymous, so "
             "the ascent grades do not change; your sessions, memberships and studies are "
             "deleted.") +
       "</p>\n";
  b += form("account-delete", "DELETE /api/account",
            "<label>" + Tr(v, "Password") +
                " <input type=\"password\" name=\"password\" id=\"delete-password\" "
                "autocomplete=\"current-password\" required></label> ",
            Tr(v, "Delete my account"), "/");
  b += "<script src=\"/static/gyms.js\" defer></script>\n";
  x.res.SetBody(200, PageLayout(v, Tr(v, "Account"), b), "text/html; charset=utf-8");
}

}  // namespace sb::web
