#pragma once
// argil::sculpt, the entry header. Modules from the bottom up: scene (models,
// tools, materials from JSON), script (timed tool poses from JSON or CSV),
// session (the deterministic session and its journal), output (tick logs,
// timing, run summary, pictures), run (a whole session from files, resumable: run_session),
// view (a finished run replayed, and the interactive page of it or of a model).

#include "argil/io.hpp"  // IWYU pragma: export

// scene
#include "argil/sculpt/scene/scene.hpp"              // IWYU pragma: export
#include "argil/sculpt/scene/version1_material.hpp"  // IWYU pragma: export
// script
#include "argil/sculpt/script/script.hpp"         // IWYU pragma: export
#include "argil/sculpt/script/stroke_script.hpp"  // IWYU pragma: export
// session
#include "argil/sculpt/session/face_refinement.hpp"  // IWYU pragma: export
#include "argil/sculpt/session/journal.hpp"          // IWYU pragma: export
#include "argil/sculpt/session/session.hpp"          // IWYU pragma: export
// output
#include "argil/sculpt/output/pictures.hpp"          // IWYU pragma: export
#include "argil/sculpt/output/run_summary.hpp"       // IWYU pragma: export
#include "argil/sculpt/output/session_pictures.hpp"  // IWYU pragma: export
#include "argil/sculpt/output/tick_log.hpp"          // IWYU pragma: export
// run
#include "argil/sculpt/run/resume_plan.hpp"     // IWYU pragma: export
#include "argil/sculpt/run/session_runner.hpp"  // IWYU pragma: export
// view
#include "argil/sculpt/view/session_replay.hpp"  // IWYU pragma: export
#include "argil/sculpt/view/view_page.hpp"       // IWYU pragma: export
