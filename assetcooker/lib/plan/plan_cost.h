#pragma once
// The measured plan's cost model: a reflector pass's time as a ratio to the classic
// environment map's, predicted linearly from what the CPU twin counts,
//     ratio = c0 + c1 fetches-per-ray + c2 object-layers,
// with the constants fitted (least squares) to the bench's measured rows (CHANGELOG.md, quoted
// in plan_cost.cpp with their source). Bytes are not in the fit: every calibration row has
// 256^2 faces and a layer count fixed by its method, so memory cannot be told apart from
// the layers there; the plan reports them and prefers fewer among equally fast candidates.
#include <string>

namespace specula {

struct CostModel {
    double c0 = 0.0, c1 = 0.0, c2 = 0.0;
    int rows = 0;             // calibration rows
    double rmsResidual = 0.0; // x envmap, over the rows
    double maxResidual = 0.0; // largest |predicted - measured|
    std::string source;

    double predict(double fetchesPerRay, int objectLayers) const {
        return c0 + c1 * fetchesPerRay + c2 * double(objectLayers);
    }
    std::string text() const; // the constants, their source and the fit error
};

// The fit over the calibration rows (computed once).
const CostModel& benchCostModel();

} // namespace specula
