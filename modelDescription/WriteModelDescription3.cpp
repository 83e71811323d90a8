// Writes a model's FMI 3.0 modelDescription.xml from the same table of variables (fmu/Model.h)
// as the FMI 2.0 one (WriteModelDescription.cpp), at build time: the same names, value
// references, causalities, units, enumerations and start values, in FMI 3.0's types (Real ->
// Float64, Integer -> Int32); beyond FMI 2.0 the independent variable time, the model's array
// outputs with their UInt64 structural parameters, fixedInternalStepSize, early return and
// event mode. Linked with one model binding; the instantiationToken is the GUID compiled in.
//
//   write_<Model>_description3 <output.xml>
#include <algorithm>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "Fmi3Interface.h"
#include "Model.h"
#include "XmlText.h"

#ifndef PLATEIMPACT_VERSION
#error "PLATEIMPACT_VERSION must be defined (the project version)"
#endif

namespace {

using description::escape;
using description::real;
using fmu::Causality;
using fmu::Variable;
using fmu::VariableType;

const char* boolText(bool x) { return x ? "true" : "false"; }

std::string startText(const Variable& v, double x) {
    switch (v.type) {
        case VariableType::Real: return real(x);
        case VariableType::Boolean: return boolText(x != 0.0);
        default: return std::to_string(static_cast<long long>(x));
    }
}

void writeHeader(std::ostream& xml, const fmu::Model& model) {
    const fmu::ModelInfo& info = model.info();
    const char* version = PLATEIMPACT_VERSION;
    xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        << "<!-- Generated at build time from the table of variables of the model binding\n"
        << "     (modelDescription/WriteModelDescription3.cpp): do not edit. -->\n"
        << "<fmiModelDescription\n  fmiVersion=\"3.0\"\n  modelName=\"" << info.modelName
        << "\"\n  instantiationToken=\"" << fmu::modelGuid() << "\"\n  description=\"" << escape(info.description)
        << "\"\n  version=\"" << version << "\"\n  generationTool=\"PlateImpact " << version << " (CMake)\"\n"
        << "  variableNamingConvention=\"flat\">\n\n";
    const char* states = boolText(info.canGetAndSetFMUstate);
    xml << "  <CoSimulation\n    modelIdentifier=\"" << info.modelIdentifier << "\"\n"
        << "    needsExecutionTool=\"false\"\n    canBeInstantiatedOnlyOncePerProcess=\"false\"\n"
        << "    canGetAndSetFMUState=\"" << states << "\"\n    canSerializeFMUState=\"" << states << "\"\n"
        << "    providesDirectionalDerivatives=\"false\"\n    providesAdjointDerivatives=\"false\"\n"
        << "    canHandleVariableCommunicationStepSize=\"true\"\n";
    if (model.fixedInternalStepSize() > 0)
        xml << "    fixedInternalStepSize=\"" << real(model.fixedInternalStepSize()) << "\"\n";
    xml << "    maxOutputDerivativeOrder=\"" << info.maxOutputDerivativeOrder << "\"\n"
        << "    providesIntermediateUpdate=\"false\"\n    mightReturnEarlyFromDoStep=\"" << boolText(model.hasEvents())
        << "\"\n    hasEventMode=\"true\"/>\n\n";
}

void writeUnits(std::ostream& xml, const fmu::Model& model) {
    std::vector<std::string> units;
    const auto add = [&](const char* unit) {
        if (unit && std::find(units.begin(), units.end(), unit) == units.end()) units.push_back(unit);
    };
    for (const Variable& v : model.variables()) add(v.unit);
    for (const fmu::ArrayOutput& a : model.arrayOutputs()) add(a.unit);
    if (units.empty()) return;
    xml << "  <UnitDefinitions>\n";
    for (const std::string& unit : units) {
        const std::string base = description::baseUnit(unit);
        xml << "    <Unit name=\"" << escape(unit) << "\"><BaseUnit" << (base.empty() ? "" : " ") << base
            << "/></Unit>\n";
    }
    xml << "  </UnitDefinitions>\n\n";
}

void writeTypes(std::ostream& xml, const std::vector<Variable>& variables) {
    std::vector<const fmu::EnumerationType*> enumerations;
    for (const Variable& v : variables)
        if (v.enumeration && std::find(enumerations.begin(), enumerations.end(), v.enumeration) == enumerations.end())
            enumerations.push_back(v.enumeration);
    if (!enumerations.empty()) {
        xml << "  <TypeDefinitions>\n";
        for (const fmu::EnumerationType* e : enumerations) {
            xml << "    <EnumerationType name=\"" << e->name << "\" description=\"" << escape(e->description)
                << "\">\n";
            for (const fmu::EnumerationItem& item : e->items)
                xml << "      <Item name=\"" << item.name << "\" value=\"" << item.value << "\" description=\""
                    << escape(item.description) << "\"/>\n";
            xml << "    </EnumerationType>\n";
        }
        xml << "  </TypeDefinitions>\n\n";
    }
    xml << "  <LogCategories>\n"
        << "    <Category name=\"logStatusError\" description=\"Messages explaining an fmi3Error or fmi3Discard "
           "return (on unless switched off)\"/>\n"
        << "    <Category name=\"logStatusWarning\" description=\"Warnings (on when loggingOn)\"/>\n"
        << "    <Category name=\"logAll\" description=\"Trace of the FMU's work: instantiation, builds, steps, "
           "early returns; setting this category switches all categories\"/>\n"
        << "  </LogCategories>\n\n";
}

// One variable of the table; its value reference joins `outputs` if it is an output.
void writeVariable(std::ostream& xml, const fmu::Model& model, const Variable& v,
                   std::vector<fmi2ValueReference>& outputs) {
    xml << "    <" << fmu::fmi3TypeName(v.type) << " name=\"" << v.name << "\" valueReference=\"" << v.vr << "\"";
    switch (v.causality) {
        case Causality::Parameter: xml << " causality=\"parameter\" variability=\"fixed\" initial=\"exact\""; break;
        case Causality::Input: xml << " causality=\"input\" variability=\"continuous\""; break;
        case Causality::Output:
            xml << " causality=\"output\" variability=\"" << (v.type == VariableType::Real ? "continuous" : "discrete")
                << "\" initial=\"calculated\"";
            outputs.push_back(v.vr);
            break;
    }
    if (v.enumeration) xml << " declaredType=\"" << v.enumeration->name << "\"";
    if (v.unit) xml << " unit=\"" << escape(v.unit) << "\"";
    if (!std::isnan(v.min)) xml << " min=\"" << startText(v, v.min) << "\"";
    if (!std::isnan(v.max)) xml << " max=\"" << startText(v, v.max) << "\"";
    if (v.causality != Causality::Output) xml << " start=\"" << startText(v, model.get(v)) << "\"";
    xml << " description=\"" << escape(v.description) << "\"/>\n";
}

void writeArrays(std::ostream& xml, const fmu::Model& model, std::vector<fmi2ValueReference>& outputs) {
    for (const fmu::StructuralParameter& s : model.structuralParameters()) {
        const Variable* base = model.find(s.parameter);
        if (!base) throw std::runtime_error(std::string(s.name) + " is a view of no parameter of the table");
        xml << "    <UInt64 name=\"" << s.name << "\" valueReference=\"" << s.vr
            << "\" causality=\"structuralParameter\" variability=\"fixed\" initial=\"exact\" start=\""
            << static_cast<long long>(model.get(*base)) + s.offset << "\" description=\"" << escape(s.description)
            << "\"/>\n";
    }
    for (const fmu::ArrayOutput& a : model.arrayOutputs()) {
        xml << "    <Float64 name=\"" << a.name << "\" valueReference=\"" << a.vr
            << "\" causality=\"output\" variability=\"continuous\" initial=\"calculated\"";
        if (a.unit) xml << " unit=\"" << escape(a.unit) << "\"";
        xml << " description=\"" << escape(a.description) << "\">\n";
        for (fmi2ValueReference extent : a.extents) xml << "      <Dimension valueReference=\"" << extent << "\"/>\n";
        xml << "    </Float64>\n";
        outputs.push_back(a.vr);
    }
}

void writeVariables(std::ostream& xml, const fmu::Model& model) {
    xml << "  <ModelVariables>\n"
        << "    <Float64 name=\"time\" valueReference=\"" << fmu::kFmi3TimeValueReference
        << "\" causality=\"independent\" variability=\"continuous\" description=\"Simulation time\"/>\n";
    std::vector<fmi2ValueReference> outputs;
    for (const Variable& v : model.variables()) writeVariable(xml, model, v, outputs);
    writeArrays(xml, model, outputs);
    xml << "  </ModelVariables>\n\n";
    // No direct feedthrough: the outputs at a communication point depend on the inputs only
    // through the steps before it.
    xml << "  <ModelStructure>\n";
    for (fmi2ValueReference vr : outputs) xml << "    <Output valueReference=\"" << vr << "\" dependencies=\"\"/>\n";
    for (fmi2ValueReference vr : outputs) xml << "    <InitialUnknown valueReference=\"" << vr << "\"/>\n";
    xml << "  </ModelStructure>\n\n</fmiModelDescription>\n";
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::cerr << "usage: " << argv[0] << " <modelDescription.xml>\n";
        return 2;
    }
    try {
        const std::unique_ptr<fmu::Model> model = fmu::createModel();
        std::ofstream xml(argv[1]);
        writeHeader(xml, *model);
        writeUnits(xml, *model);
        writeTypes(xml, model->variables());
        xml << "  <DefaultExperiment startTime=\"0\" stopTime=\"" << real(model->info().defaultStopTime)
            << "\" stepSize=\"" << real(model->info().defaultStepSize) << "\"/>\n\n";
        writeVariables(xml, *model);
        if (!xml) throw std::runtime_error(std::string("cannot write ") + argv[1]);
    } catch (const std::exception& e) {
        std::cerr << argv[0] << ": " << e.what() << "\n";
        return 1;
    }
    return 0;
}
