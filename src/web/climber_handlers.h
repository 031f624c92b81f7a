// Internal to web/: the handlers of the climbers' side (issues 14 and 15):
// the feedback page behind the route card's QR code, the setter's views,
// studies and their API (docs/web.md). Bound to paths in server.cc.
#ifndef SB_WEB_CLIMBER_HANDLERS_H_
#define SB_WEB_CLIMBER_HANDLERS_H_

#include <string>

#include "app/types.h"
#include "web/handlers.h"

namespace sb::web {

// The cookie holding a climber's participant token (HttpOnly, two years).
inline constexpr char kParticipantCookie[] = "sb_climber";

// Pages.
void PageFeedback(Exchange& x);         // GET /r/{id}
void PageFeedbackAnswers(Exchange& x);  // GET /r/{id}/responses (owner)
void PageDrift(Exchange& x);            // GET /drift (logged in)
void PageStudies(Exchange& x);          // GET /studies
void PageNewStudy(Exchange& x);         // GET /studies/new
void PageEditStudy(Exchange& x);        // GET /studies/{id}/edit (owner)
void PageStudyResults(Exchange& x);     // GET /studies/{id} (owner)
void PageStudyForm(Exchange& x);        // GET /s/{id} (anyone)
// Owner-only downloads.
void GetStudyResponsesCsv(Exchange& x);     // GET /studies/{id}/responses.csv
void GetStudyInstrument(Exchange& x);       // GET /studies/{id}/instrument.json
void GetStudyDemographicsCsv(Exchange& x);  // GET /studies/{id}/demographics.csv
void GetStudyAnalysis(Exchange& x);         // GET /studies/{id}/analysis.json
void GetStudyBoxPlot(Exchange& x);          // GET /studies/{id}/boxplot.svg
// JSON API.
void PostRouteFeedback(Exchange& x);  // POST /api/r/{id}/feedback
void PostStudy(Exchange& x);          // POST /api/studies
void PutStudy(Exchange& x);           // PUT /api/studies/{id}
void PostStudyResponse(Exchange& x);  // POST /api/s/{id}/responses
// The burst rule on study responses (issue 23, app/burst.h), owner only:
void GetStudyHeld(Exchange& x);              // GET /api/studies/{id}/held
void PostStudyResponseAccept(Exchange& x);   // POST /api/studies/{id}/responses/{response}/accept
void PostStudyResponseDiscard(Exchange& x);  // POST .../responses/{response}/discard

// The consensus block of the route and variation pages for `route` as the
// caller sees it ("" when it cannot be made; the reason is logged).
std::string ConsensusBlock(Exchange& x, const app::RouteView& route);

}  // namespace sb::web

#endif  // SB_WEB_CLIMBER_HANDLERS_H_
