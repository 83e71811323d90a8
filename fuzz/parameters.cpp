// libFuzzer harness (c): every parameter of the table at and past the edges of its range (and
// any value), then initialization and one short step. Whatever the FMU accepts it must run:
// after an accepted initialization and step, every Real output is finite (a finding otherwise).
// Mesh sizes stay small (a large mesh is legal, only slow).
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "FuzzSupport.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    FuzzedDataProvider in(data, size);
    static const std::unique_ptr<fmu::Model> table = fmu::createModel();  // the variables, for their types
    fmi2Component c = fuzz::instantiate();
    fuzz::smallPlate(c, 1, 1);
    fmi2EnterInitializationMode(c);
    for (const fmu::Variable& v : table->variables()) {
        if (v.causality == fmu::Causality::Output || !in.ConsumeBool()) continue;
        switch (v.type) {
            case fmu::VariableType::Real: {
                const fmi2Real x = fuzz::awkwardReal(in);
                fmi2SetReal(c, &v.vr, 1, &x);
                break;
            }
            case fmu::VariableType::Integer: {
                const bool size = v.vr == fuzz::kNx || v.vr == fuzz::kNy || v.vr == fuzz::kModes;
                const fmi2Integer x = size ? in.ConsumeIntegralInRange(-1, 2) : in.ConsumeIntegralInRange(-2, 5);
                fmi2SetInteger(c, &v.vr, 1, &x);
                break;
            }
            case fmu::VariableType::Boolean: {
                const fmi2Boolean x = in.ConsumeBool();
                fmi2SetBoolean(c, &v.vr, 1, &x);
                break;
            }
        }
    }
    if (fmi2ExitInitializationMode(c) == fmi2OK) {
        fmi2Real dt = 0.0;
        const fmi2ValueReference dtVr = fuzz::kDt;
        fmi2GetReal(c, &dtVr, 1, &dt);
        const int steps = in.ConsumeIntegralInRange(1, 5);
        if (fmi2DoStep(c, 0.0, steps * dt, fmi2True) == fmi2OK) {
            for (const fmu::Variable& v : table->variables()) {
                if (v.causality != fmu::Causality::Output || v.type != fmu::VariableType::Real) continue;
                fmi2Real x = 0.0;
                fmi2GetReal(c, &v.vr, 1, &x);
                if (!std::isfinite(x)) {  // accepted parameters, non-finite output: say which
                    for (const fmu::Variable& p : table->variables()) {
                        if (p.causality != fmu::Causality::Parameter) continue;
                        fmi2Real value = 0.0;
                        fmi2Integer item = 0;
                        if (p.type == fmu::VariableType::Real)
                            fmi2GetReal(c, &p.vr, 1, &value);
                        else if (p.type != fmu::VariableType::Boolean)
                            fmi2GetInteger(c, &p.vr, 1, &item), value = item;
                        std::fprintf(stderr, "  %s = %.17g\n", p.name, value);
                    }
                    std::fprintf(stderr, "fuzz_parameters: %s = %g after an accepted step\n", v.name, x);
                    std::abort();
                }
            }
        }
    }
    fmi2FreeInstance(c);
    return 0;
}
