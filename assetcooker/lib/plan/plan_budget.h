#pragma once
// The error budget a probe node's markup member "max_error" sets (the same text as
// --max-error, or a number meaning dB; settings/error_budget.h).
#include "assetcooker/lib/scene/scene_markup.h"
#include "assetcooker/lib/settings/error_budget.h"

#include <string>

namespace specula {

// The probe node's "max_error" (markupProbe indexes markup.probes; out of range: none).
// Throws Error(node, "specula_probe.max_error", ...) on a value of the wrong type or one
// parseErrorBudget refuses.
ErrorBudget markupErrorBudget(const SceneMarkup& markup, int markupProbe);

} // namespace specula
