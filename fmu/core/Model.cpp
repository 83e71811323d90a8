#include "core/Model.h"

#include <algorithm>
#include <string>

namespace fmu {

const char* typeName(VariableType type) {
    switch (type) {
        case VariableType::Real: return "Real";
        case VariableType::Integer: return "Integer";
        case VariableType::Boolean: return "Boolean";
    }
    return "?";
}

bool EnumerationType::contains(int value) const {
    for (const EnumerationItem& item : items)
        if (item.value == value) return true;
    return false;
}

std::string EnumerationType::itemList() const {
    std::string text;
    for (const EnumerationItem& item : items) {
        if (!text.empty()) text += ", ";
        text += std::to_string(item.value) + " = " + item.name;
    }
    return text;
}

Variable integerSwitch(ValueReference vr, const char* name, const char* description, const EnumerationType& items) {
    Variable v{vr, name, VariableType::Integer, Causality::Parameter, description, nullptr, &items, true, false};
    const auto [low, high] = std::minmax_element(items.items.begin(), items.items.end(),
                                                 [](const auto& a, const auto& b) { return a.value < b.value; });
    v.min = low->value;
    v.max = high->value;
    return v;
}

const Variable* Model::find(ValueReference vr) const {
    for (const Variable& v : variables())
        if (v.vr == vr && (v.version == 0 || v.version == fmiVersion_)) return &v;
    return nullptr;
}

const StructuralParameter* Fmi3Features::findStructural(ValueReference vr) const {
    for (const StructuralParameter& s : structuralParameters())
        if (s.vr == vr) return &s;
    return nullptr;
}

const ArrayVariable* Fmi3Features::findArray(ValueReference vr) const {
    for (const ArrayVariable& a : arrayVariables())
        if (a.vr == vr) return &a;
    return nullptr;
}

void Model::setInputDerivative(const Variable& v, int, double) {
    throw ModelError(std::string(v.name) + " takes no input derivatives");
}

bool Fmi3Features::doStepUntilEvent(double, double) {
    throw ModelError("internal error: an early return asked of a model without events");
}

void Fmi3Features::setIntermediate(const Variable& v, double) {
    throw ModelError(std::string(v.name) + " takes no intermediate values");
}

double Model::getOutputDerivative(const Variable& v, int) const {
    throw ModelError(std::string(v.name) + " has no output derivatives");
}

const std::vector<StructuralParameter>& Fmi3Features::structuralParameters() const {
    static const std::vector<StructuralParameter> none;
    return none;
}

const std::vector<ArrayVariable>& Fmi3Features::arrayVariables() const {
    static const std::vector<ArrayVariable> none;
    return none;
}

const std::vector<Terminal>& Fmi3Features::terminals() const {
    static const std::vector<Terminal> none;
    return none;
}

void Fmi3Features::getArray(const ArrayVariable& a, double*, std::size_t) const {
    throw ModelError(std::string(a.name) + " is not an array of this model");
}

void Fmi3Features::setArray(const ArrayVariable& a, const double*, std::size_t) {
    throw ModelError(std::string(a.name) + " is not a settable array of this model");
}

double Fmi3Features::ownStructuralValue(const StructuralParameter& s) const {
    for (const auto& [vr, value] : ownStructuralValues_)
        if (vr == s.vr) return value;
    return s.offset;
}

void Fmi3Features::setOwnStructuralValue(const StructuralParameter& s, double value) {
    for (auto& [vr, stored] : ownStructuralValues_)
        if (vr == s.vr) {
            stored = value;
            return;
        }
    ownStructuralValues_.emplace_back(s.vr, value);
}

}  // namespace fmu
