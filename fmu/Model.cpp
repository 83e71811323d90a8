#include "Model.h"

#include <string>

namespace fmu {

const char* typeName(VariableType type) {
    switch (type) {
        case VariableType::Real: return "Real";
        case VariableType::Integer: return "Integer";
        case VariableType::Boolean: return "Boolean";
        case VariableType::Enumeration: return "Enumeration";
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
        text += std::string(item.name) + " = " + std::to_string(item.value);
    }
    return text;
}

const Variable* Model::find(fmi2ValueReference vr) const {
    for (const Variable& v : variables())
        if (v.vr == vr) return &v;
    return nullptr;
}

void Model::setInputDerivative(const Variable& v, int, double) {
    throw ModelError(std::string(v.name) + " takes no input derivatives");
}

double Model::getOutputDerivative(const Variable& v, int) const {
    throw ModelError(std::string(v.name) + " has no output derivatives");
}

const std::vector<StructuralParameter>& Model::structuralParameters() const {
    static const std::vector<StructuralParameter> none;
    return none;
}

const std::vector<ArrayOutput>& Model::arrayOutputs() const {
    static const std::vector<ArrayOutput> none;
    return none;
}

void Model::getArray(const ArrayOutput& a, double*, std::size_t) const {
    throw ModelError(std::string(a.name) + " is not an array output of this model");
}

}  // namespace fmu
