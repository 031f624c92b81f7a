// The reply to a refused page model (app/page_models.h), shared by the
// handlers that call one.
#ifndef SB_WEB_MODEL_REPLY_H_
#define SB_WEB_MODEL_REPLY_H_

#include "base/status.h"
#include "web/handlers.h"

namespace sb::web {

// Replies to a page model's refusal `s`: the work budget's
// kResourceExhausted as AdmitWork's (429, with Retry-After
// `retry_after_seconds` when > 0; JSON for /api/, else an error page),
// anything else as ApiError (/api/) or PageError.
void ModelError(Exchange& x, const Status& s, int retry_after_seconds);

}  // namespace sb::web

#endif  // SB_WEB_MODEL_REPLY_H_
