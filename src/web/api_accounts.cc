// JSON API: accounts and sessions.
#include <algorithm>

#include "base/log.h"
#include "base/text.h"
#include "web/handlers.h"
#include "web/logbook_handlers.h"

namespace sb::web {

using nlohmann::json;

namespace {

std::string SessionCookie(const ServerOptions& o, const std::string& value, int max_age) {
  return std::string(kSessionCookie) + "=" + value + "; Path=/; HttpOnly; SameSite=Lax; Max-Age=" +
         std::to_string(max_age) + (o.secure_cookie ? "; Secure" : "");
}

// {"username", "password"} from the body.
Status Credentials(const Request& req, std::string* user, std::string* pass) {
  SB_ASSIGN_OR_RETURN(json body, BodyObject(req));
  SB_ASSIGN_OR_RETURN(*user, StringField(body, "username"));
  SB_ASSIGN_OR_RETURN(*pass, StringField(body, "password"));
  return Status::Ok();
}

// The password-check queue is full: 503 with Retry-After (the server's
// state, not the caller's fault).
void Busy(Exchange& x, const Status& s, int retry_after) {
  x.res.SetHeader("Retry-After", std::to_string(std::max(1, retry_after)));
  ReplyJson(x.res, 503, json{{"error", s.message()}});
}

}  // namespace

void PostUsers(Exchange& x) {
  std::string user, pass;
  if (Status s = Credentials(x.req, &user, &pass); !s.ok()) return ApiError(x, s);
  // Issue 32: "display_name" and "language", checked before the account is made.
  std::optional<std::string> display_name, language;
  {
    Result<json> body = BodyObject(x.req);
    if (!body.ok()) return ApiError(x, body.status());
    for (auto [field, out] : {std::pair<const char*, std::optional<std::string>*>{
                                  "display_name", &display_name},
                              {"language", &language}}) {
      if (!body->contains(field) || (*body)[field].is_null()) continue;
      Result<std::string> v = StringField(*body, field);
      if (!v.ok()) return ApiError(x, v.status());
      *out = std::string(Trim(*v));
    }
    if (display_name && !display_name->empty()) {
      if (Status s = app::CheckDisplayName(*display_name); !s.ok()) return ApiError(x, s);
    }
    if (language && !language->empty() && !app::IsLanguage(*language)) {
      return ApiError(x, Status::InvalidInput("language: one of en, de, fr"));
    }
  }
  bool busy = false;
  Result<app::User> u = x.services.accounts.SignUp(user, pass, x.caller.viewer.address, &busy);
  if (!u.ok()) {
    if (busy) return Busy(x, u.status(), 1);
    return ApiError(x, u.status());
  }
  // The install's first gym's first account is its head setter (issue 21).
  if (Status g = x.services.gyms.Welcome(u->id); !g.ok()) LogError("welcome: " + g.message());
  if (Status p = x.services.profiles.Init(u->id, display_name, language); !p.ok()) {
    LogError("profile: " + p.message());
  }
  ReplyJson(x.res, 201, json{{"id", u->id},
                             {"username", u->username},
                             {"display_name", display_name.value_or("")},
                             {"language", language.value_or("")}});
}

void PostSessions(Exchange& x) {
  std::string user, pass;
  if (Status s = Credentials(x.req, &user, &pass); !s.ok()) return ApiError(x, s);
  int retry_after = 0;
  bool busy = false;
  Result<app::NewSession> s =
      x.services.accounts.LogIn(user, pass, x.caller.viewer.address, &retry_after, &busy);
  if (!s.ok()) {
    if (busy) return Busy(x, s.status(), retry_after);
    if (retry_after > 0) x.res.SetHeader("Retry-After", std::to_string(retry_after));
    return ApiError(x, s.status());
  }
  MergeDeviceTicks(x, s->session.user_id);  // the phone's ticks join the logbook
  x.res.SetHeader("Set-Cookie",
                  SessionCookie(x.options, s->token, x.services.options.session_seconds));
  ReplyJson(x.res, 200,
            json{{"csrf", s->session.csrf},
                 {"username", s->session.username},
                 {"id", s->session.user_id}});
}

void DeleteSessions(Exchange& x) {
  if (Status s = x.services.accounts.LogOut(x.caller.session_token); !s.ok()) {
    return ApiError(x, s);
  }
  x.res.SetHeader("Set-Cookie", SessionCookie(x.options, "", 0));
  x.res.status = 204;
}

void GetSession(Exchange& x) {
  const app::Viewer& v = x.caller.viewer;
  if (!v.logged_in()) return ReplyJson(x.res, 200, json{{"logged_in", false}});
  ReplyJson(x.res, 200,
            json{{"logged_in", true},
                 {"username", v.username},
                 {"id", *v.user_id},
                 {"csrf", x.caller.csrf}});
}

}  // namespace sb::web
