#pragma once
// The page vsi serve shows at `/`: the store's studies with their progress,
// ETA and verdict, links to their envelopes and report, and a form to submit
// a study. One self-contained document (no external assets: it works
// offline); it polls the API every 2 s.
#include <string_view>

namespace railvsi::scheduler {

std::string_view dashboard_html();

}  // namespace railvsi::scheduler
