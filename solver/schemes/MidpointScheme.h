#pragma once
// time_scheme = conserving (docs/theory.md §17): every step one midpoint step of Δt with the
// discrete gradient of the contact potential (CondensedScheme), so the energy identity (T.17d)
// holds exactly at any Δt, through impacts.
#include <memory>

#include "schemes/CondensedScheme.h"

namespace plate {

class MidpointScheme final : public CondensedScheme {
public:
    MidpointScheme(std::shared_ptr<const CondensedPlate> plate, Obstacles obstacles, const LawParameters& law,
                   OutputRows rows = {})
        : CondensedScheme(std::move(plate), obstacles, law, std::move(rows)) {}

private:
    void advance(double zNext, double pNext) override {
        now().rowsKnown = false;  // the rows at t_n gathered afresh: the conserving law's results as they always were
        midpointStep(everyRow(), now(), now().s.zPrev, zNext, pNext);
    }
};

}  // namespace plate
