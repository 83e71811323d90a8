// Writes a model's modelDescription.xml from its table of variables (fmu/Model.h), at build
// time: the table is the one source of the interface, so the XML, the binary and the FMU
// states cannot disagree. Linked with one model binding; the GUID is the one compiled into it.
//
//   write_model_description <output.xml>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "Model.h"
#include "XmlText.h"

#ifndef PLATEIMPACT_VERSION
#error "PLATEIMPACT_VERSION must be defined (the project version)"
#endif

namespace {

using fmu::Causality;
using fmu::Variable;
using fmu::VariableType;

// The XML text helpers shared with the FMI 3.0 writer (XmlText.h).
using description::baseUnit;
using description::escape;
using description::real;

std::string startText(const Variable& v, double x) {
    switch (v.type) {
        case VariableType::Real: return real(x);
        case VariableType::Boolean: return x != 0.0 ? "true" : "false";
        default: return std::to_string(static_cast<long long>(x));
    }
}

void writeHeader(std::ostream& xml, const fmu::ModelInfo& info) {
    const char* version = PLATEIMPACT_VERSION;
    xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        << "<!-- Generated at build time from the table of variables of the model binding\n"
        << "     (modelDescription/WriteModelDescription.cpp): do not edit. -->\n"
        << "<fmiModelDescription\n  fmiVersion=\"2.0\"\n  modelName=\"" << info.modelName << "\"\n  guid=\""
        << fmu::modelGuid() << "\"\n  description=\"" << escape(info.description) << "\"\n  version=\"" << version
        << "\"\n  generationTool=\"PlateImpact " << version << " (CMake)\"\n"
        << "  variableNamingConvention=\"flat\"\n  numberOfEventIndicators=\"0\">\n\n";
    const char* states = info.canGetAndSetFMUstate ? "true" : "false";
    xml << "  <CoSimulation\n    modelIdentifier=\"" << info.modelIdentifier << "\"\n"
        << "    needsExecutionTool=\"false\"\n    canHandleVariableCommunicationStepSize=\"true\"\n"
        << "    canInterpolateInputs=\"" << (info.canInterpolateInputs ? "true" : "false") << "\"\n"
        << "    maxOutputDerivativeOrder=\"" << info.maxOutputDerivativeOrder << "\"\n"
        << "    canRunAsynchronuously=\"false\"\n    canBeInstantiatedOnlyOncePerProcess=\"false\"\n"
        << "    canNotUseMemoryManagementFunctions=\"true\"\n    canGetAndSetFMUstate=\"" << states << "\"\n"
        << "    canSerializeFMUstate=\"" << states << "\"\n    providesDirectionalDerivative=\"false\"/>\n\n";
}

void writeTypes(std::ostream& xml, const std::vector<Variable>& variables) {
    std::vector<std::string> units;
    std::vector<const fmu::EnumerationType*> enumerations;
    for (const Variable& v : variables) {
        if (v.unit && std::find(units.begin(), units.end(), v.unit) == units.end()) units.push_back(v.unit);
        if (v.enumeration && std::find(enumerations.begin(), enumerations.end(), v.enumeration) == enumerations.end())
            enumerations.push_back(v.enumeration);
    }
    if (!units.empty()) {
        xml << "  <UnitDefinitions>\n";
        for (const std::string& unit : units) {
            const std::string base = baseUnit(unit);
            xml << "    <Unit name=\"" << escape(unit) << "\"><BaseUnit" << (base.empty() ? "" : " ") << base
                << "/></Unit>\n";
        }
        xml << "  </UnitDefinitions>\n\n";
    }
    if (!enumerations.empty()) {
        xml << "  <TypeDefinitions>\n";
        for (const fmu::EnumerationType* e : enumerations) {
            xml << "    <SimpleType name=\"" << e->name << "\" description=\"" << escape(e->description)
                << "\">\n      <Enumeration>\n";
            for (const fmu::EnumerationItem& item : e->items)
                xml << "        <Item name=\"" << item.name << "\" value=\"" << item.value << "\" description=\""
                    << escape(item.description) << "\"/>\n";
            xml << "      </Enumeration>\n    </SimpleType>\n";
        }
        xml << "  </TypeDefinitions>\n\n";
    }
    xml << "  <LogCategories>\n"
        << "    <Category name=\"logStatusError\" description=\"Messages explaining an fmi2Error or fmi2Discard "
           "return (on unless switched off)\"/>\n"
        << "    <Category name=\"logStatusWarning\" description=\"Warnings (on when loggingOn)\"/>\n"
        << "    <Category name=\"logInfo\" description=\"What an initialization will cost (memory, time, "
           "before it is spent) and its progress (on when loggingOn)\"/>\n"
        << "    <Category name=\"logAll\" description=\"Trace of the FMU's work: instantiation, builds, steps; "
           "setting this category switches all categories\"/>\n"
        << "  </LogCategories>\n\n";
}

void writeVariables(std::ostream& xml, const fmu::Model& model) {
    const std::vector<Variable>& variables = model.variables();
    xml << "  <ModelVariables>\n";
    std::vector<std::size_t> outputs;
    for (std::size_t i = 0; i < variables.size(); ++i) {
        const Variable& v = variables[i];
        xml << "    <!-- index " << i + 1 << " --><ScalarVariable name=\"" << v.name << "\" valueReference=\"" << v.vr
            << "\"";
        switch (v.causality) {
            case Causality::Parameter: xml << " causality=\"parameter\" variability=\"fixed\" initial=\"exact\""; break;
            case Causality::Input: xml << " causality=\"input\" variability=\"continuous\""; break;
            case Causality::Output:
                xml << " causality=\"output\" variability=\""
                    << (v.type == VariableType::Real ? "continuous" : "discrete") << "\" initial=\"calculated\"";
                outputs.push_back(i + 1);
                break;
        }
        xml << " description=\"" << escape(v.description) << "\">\n      <" << fmu::typeName(v.type);
        if (v.enumeration) xml << " declaredType=\"" << v.enumeration->name << "\"";
        if (v.unit) xml << " unit=\"" << escape(v.unit) << "\"";
        if (!std::isnan(v.min)) xml << " min=\"" << startText(v, v.min) << "\"";
        if (!std::isnan(v.max)) xml << " max=\"" << startText(v, v.max) << "\"";
        if (v.causality != Causality::Output) xml << " start=\"" << startText(v, model.get(v)) << "\"";
        xml << "/></ScalarVariable>\n";
    }
    xml << "  </ModelVariables>\n\n";
    // No direct feedthrough: the outputs at a communication point depend on the inputs only
    // through the steps before it.
    xml << "  <ModelStructure>\n    <Outputs>\n";
    for (std::size_t index : outputs) xml << "      <Unknown index=\"" << index << "\" dependencies=\"\"/>\n";
    xml << "    </Outputs>\n    <InitialUnknowns>\n";
    for (std::size_t index : outputs) xml << "      <Unknown index=\"" << index << "\"/>\n";
    xml << "    </InitialUnknowns>\n  </ModelStructure>\n\n</fmiModelDescription>\n";
}

// documentation/index.html (FMI 2.0, section 2.4): the model's own page and the same table of
// variables the XML declares.
void writeDocumentation(std::ostream& html, const fmu::Model& model) {
    const fmu::ModelInfo& info = model.info();
    html << "<!DOCTYPE html>\n<html lang=\"en\">\n<head><meta charset=\"utf-8\"><title>" << info.modelName
         << "</title>\n<style>body{font-family:sans-serif;max-width:60em;margin:2em auto;line-height:1.4}"
            "table{border-collapse:collapse}td,th{border:1px solid #bbb;padding:.2em .5em;vertical-align:top}"
            "</style></head>\n<body>\n<h1>"
         << info.modelName << "</h1>\n<p>" << escape(info.description) << "</p>\n";
    if (info.documentationHtml) html << info.documentationHtml;
    html << "<h2>Variables</h2>\n<table>\n<tr><th>name</th><th>value reference</th><th>causality</th><th>type</th>"
            "<th>start</th><th>min</th><th>max</th><th>unit</th><th>description</th></tr>\n";
    for (const Variable& v : model.variables()) {
        const char* causality = v.causality == Causality::Parameter ? "parameter"
                                : v.causality == Causality::Input   ? "input"
                                                                    : "output";
        html << "<tr><td><code>" << v.name << "</code></td><td>" << v.vr << "</td><td>" << causality << "</td><td>"
             << fmu::typeName(v.type);
        if (v.enumeration) {
            html << " (";
            for (std::size_t k = 0; k < v.enumeration->items.size(); ++k)
                html << (k ? ", " : "") << v.enumeration->items[k].name << " = " << v.enumeration->items[k].value;
            html << ")";
        }
        html << "</td><td>" << (v.causality == Causality::Output ? "" : escape(startText(v, model.get(v))))
             << "</td><td>" << (std::isnan(v.min) ? "" : startText(v, v.min)) << "</td><td>"
             << (std::isnan(v.max) ? "" : startText(v, v.max)) << "</td><td>" << (v.unit ? escape(v.unit) : "")
             << "</td><td>" << escape(v.description) << "</td></tr>\n";
    }
    html << "</table>\n</body>\n</html>\n";
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2 && argc != 3) {
        std::cerr << "usage: " << argv[0] << " <modelDescription.xml> [<documentation/index.html>]\n";
        return 2;
    }
    try {
        const std::unique_ptr<fmu::Model> model = fmu::createModel();
        std::ofstream xml(argv[1]);
        writeHeader(xml, model->info());
        writeTypes(xml, model->variables());
        xml << "  <DefaultExperiment startTime=\"0\" stopTime=\"" << real(model->info().defaultStopTime)
            << "\" stepSize=\"" << real(model->info().defaultStepSize) << "\"/>\n\n";
        writeVariables(xml, *model);
        if (!xml) throw std::runtime_error(std::string("cannot write ") + argv[1]);
        if (argc == 3) {
            std::ofstream html(argv[2]);
            writeDocumentation(html, *model);
            if (!html) throw std::runtime_error(std::string("cannot write ") + argv[2]);
        }
    } catch (const std::exception& e) {
        std::cerr << argv[0] << ": " << e.what() << "\n";
        return 1;
    }
    return 0;
}
