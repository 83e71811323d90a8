// The instance's FMU states (core/Instance.h): a snapshot of the table's settable values, the
// instance's state and start time and the model's own part (Model::saveState), taken, set all or
// nothing, and serialized with its header and checksum (core/StateFormat.h).
#include <memory>

#include "core/Instance.h"
#include "core/StateFormat.h"

namespace fmu {

void Instance::capture(Snapshot& snapshot) const {
    snapshot.state = state_;
    snapshot.startTime = startTime_;
    snapshot.values.clear();
    for (const Variable& v : model_->variables())
        if (isSettable(v)) snapshot.values.push_back(model_->get(v));
    snapshot.modelState.clear();
    model_->saveState(snapshot.modelState);
}

void Instance::restore(const Snapshot& snapshot) {
    const auto apply = [this](const Snapshot& s) {
        std::size_t next = 0;
        for (const Variable& v : model_->variables())
            if (isSettable(v)) model_->set(v, s.values.at(next++));
        const double* in = s.modelState.data();
        model_->restoreState(in, in + s.modelState.size());
        state_ = s.state;
        startTime_ = s.startTime;
    };
    // All or nothing: a state the model refuses (its part is checked only here) leaves the
    // instance as it was.
    Snapshot before;
    capture(before);
    try {
        apply(snapshot);
    } catch (...) {
        apply(before);
        throw;
    }
}

Status Instance::getState(StateHandle* state) {
    if (!state) return fail("argument FMUstate must not be NULL");
    if (*state) {  // reuse a state this FMU handed out before
        Snapshot* previous = asSnapshot(*state);
        if (!previous) return fail("*FMUstate is not an FMU state of %s", model_->info().modelName);
        capture(*previous);
        return Status::OK;
    }
    auto snapshot = std::make_unique<Snapshot>();
    capture(*snapshot);
    *state = snapshot.release();  // owned by the importer until freeState
    return Status::OK;
}

Status Instance::setState(StateHandle state) {
    const Snapshot* snapshot = asSnapshot(state);
    if (!snapshot) return fail("FMUstate is NULL or not an FMU state of %s", model_->info().modelName);
    restore(*snapshot);
    return Status::OK;
}

Status Instance::freeState(StateHandle* state) {
    if (!state) return fail("argument FMUstate must not be NULL");
    if (!*state) return Status::OK;
    Snapshot* snapshot = asSnapshot(*state);
    if (!snapshot) return fail("*FMUstate is not an FMU state of %s", model_->info().modelName);
    std::unique_ptr<Snapshot> owned(snapshot);  // takes ownership back and frees it
    *state = nullptr;
    return Status::OK;
}

Status Instance::serializedStateSize(StateHandle state, std::size_t* size) {
    const Snapshot* snapshot = asSnapshot(state);
    if (!snapshot) return fail("FMUstate is NULL or not an FMU state of %s", model_->info().modelName);
    if (!size) return fail("argument size must not be NULL");
    *size = serializedSize(*snapshot);
    return Status::OK;
}

Status Instance::serializeState(StateHandle state, Byte serialized[], std::size_t size) {
    const Snapshot* snapshot = asSnapshot(state);
    if (!snapshot) return fail("FMUstate is NULL or not an FMU state of %s", model_->info().modelName);
    if (!serialized) return fail("argument serializedState must not be NULL");
    const std::size_t expected = serializedSize(*snapshot);
    if (size != expected)
        return fail("size = %zu, but the state needs %zu bytes (%s)", size, expected, names_.serializedStateSize);
    serialize(*snapshot, *model_, modelGuid(), serialized, size);
    return Status::OK;
}

Status Instance::deserializeState(const Byte serialized[], std::size_t size, StateHandle* state) {
    if (!state) return fail("argument FMUstate must not be NULL");
    if (!serialized && size > 0) return fail("argument serializedState must not be NULL");
    if (*state && !asSnapshot(*state)) return fail("*FMUstate is not an FMU state of %s", model_->info().modelName);
    Snapshot decoded;
    try {
        decoded = deserialize(serialized, size, modelGuid(), *model_);
    } catch (const CorruptState& e) {
        return fail("corrupt serialized state: %s", e.what());
    } catch (const ForeignState& e) {
        return fail("serialized state of another platform refused: %s", e.what());
    }
    if (*state) {
        *asSnapshot(*state) = std::move(decoded);
        return Status::OK;
    }
    *state = std::make_unique<Snapshot>(std::move(decoded)).release();  // the importer's until freeState
    return Status::OK;
}

}  // namespace fmu
