// Writes a model's modelDescription.xml and documentation/index.html, FMI 2.0 or FMI 3.0, from
// its table of variables (fmu/core/Model.h), at build time: the table is the one source of the
// interface, so the XML, the binary and the FMU states cannot disagree. Linked with one model
// binding; the GUID (FMI 3.0: instantiationToken) is the one compiled into it.
//
//   write_<Model>_description <2|3> <modelDescription.xml> <index.html> [--terminals=<path>]
//                             [<name>:<SPDX>:<path> ...]
//
// --terminals=<path> (FMI 3.0): also terminalsAndIcons.xml from the binding's terminals.
// The trailing arguments are the licence entries the FMU ships in documentation/licenses/
// (fmu/CMakeLists.txt): the `license` attribute and the page name them. What the two versions
// share (metadata, units, log categories, the page) is written once; what differs is an Emitter:
// Fmi2Emitter (ScalarVariable, Unknown indices) and Fmi3Emitter (typed elements, time, arrays,
// structural parameters, fixedInternalStepSize, early return).
//
// Descriptions and the model's page may hold text for one version only: "{fmi2:...}" is kept in
// FMI 2.0 and dropped in FMI 3.0, "{fmi3:...}" the other way round, and "fmiX" becomes "fmi2" or
// "fmi3" (forVersion), so that neither version names the other's functions.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "fmi3/Fmi3Interface.h"
#include "core/Model.h"
#include "XmlText.h"

#if !defined(PLATEIMPACT_VERSION) || !defined(PLATEIMPACT_AUTHOR) || !defined(PLATEIMPACT_LICENSE) || \
    !defined(PLATEIMPACT_COPYRIGHT)
#error "PLATEIMPACT_VERSION, _AUTHOR, _LICENSE and _COPYRIGHT must be defined (fmu/CMakeLists.txt)"
#endif

namespace {

using description::escape;
using description::real;
using fmu::Causality;
using fmu::Variable;
using fmu::VariableType;

const char* boolText(bool x) { return x ? "true" : "false"; }

// One licence entry of the command line: documentation/licenses/<name>.txt under <spdx>.
struct License {
    std::string name, spdx;
};

License parseLicense(const std::string& entry) {
    const std::size_t a = entry.find(':');
    const std::size_t b = a == std::string::npos ? a : entry.find(':', a + 1);
    if (b == std::string::npos) throw std::runtime_error("licence entry \"" + entry + "\" is not <name>:<SPDX>:<path>");
    return {entry.substr(0, a), entry.substr(a + 1, b - a - 1)};
}

// The text of `text` for FMI `version` (2 or 3): {fmi2:...} and {fmi3:...} kept or dropped,
// "fmiX" named for the version.
std::string forVersion(const std::string& text, int version) {
    std::string out;
    for (std::size_t at = 0; at < text.size();) {
        if (text.compare(at, 5, "{fmi2") == 0 || text.compare(at, 5, "{fmi3") == 0) {
            const bool keep = text[at + 4] - '0' == version;
            const std::size_t end = text.find('}', at);
            if (end == std::string::npos || text[at + 5] != ':')
                throw std::runtime_error("unterminated {fmiN:...} in \"" + text + "\"");
            if (keep) out += forVersion(text.substr(at + 6, end - at - 6), version);
            at = end + 1;
        } else if (text.compare(at, 4, "fmiX") == 0) {
            out += "fmi" + std::to_string(version);
            at += 4;
        } else {
            out += text[at++];
        }
    }
    return out;
}

std::string startText(const Variable& v, double x) {
    switch (v.type) {
        case VariableType::Real: return real(x);
        case VariableType::Boolean: return boolText(x != 0.0);
        default: return std::to_string(static_cast<long long>(x));
    }
}

// A variable's description as both versions declare it: an Integer switch lists its items.
std::string describe(const Variable& v, int version) {
    std::string text = forVersion(v.description, version);
    if (v.enumeration) text += " (" + v.enumeration->itemList() + ")";
    return text;
}

std::string generationDateAndTime() {
    // SOURCE_DATE_EPOCH (reproducible builds) when set, else now; UTC, as xs:dateTime.
    std::time_t t = std::time(nullptr);
    if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH")) t = static_cast<std::time_t>(std::atoll(epoch));
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
    return text;
}

std::string licenseText(const std::vector<License>& licenses) {
    std::string text = PLATEIMPACT_LICENSE;
    std::string parts;
    for (const License& l : licenses) {
        if (l.name == "PlateImpact") continue;  // the project's own: the first words
        parts += (parts.empty() ? "" : ", ") + l.name + " (" + l.spdx + ")";
    }
    if (!parts.empty()) text += "; the binaries also contain " + parts;
    return text + "; texts in documentation/licenses";
}

class Emitter {
public:
    explicit Emitter(int version) : version(version) {}
    virtual ~Emitter() = default;
    const int version;

    virtual const char* typeName(VariableType type) const = 0;
    // <fmiModelDescription ...> after the common attributes, and <CoSimulation .../>.
    virtual void header(std::ostream& xml, const fmu::Model& model) const = 0;
    virtual void variables(std::ostream& xml, const fmu::Model& model) const = 0;
    // Rows of the page's table beyond the model's table (FMI 3.0: time, arrays).
    virtual void extraRows(std::ostream&, const fmu::Model&) const {}
};

// The table's rows this version declares (a row of one version only: Variable::version), as the
// model's own (its accessors know a row by its place in the table).
std::vector<std::reference_wrapper<const Variable>> rowsOf(const fmu::Model& model) {
    std::vector<std::reference_wrapper<const Variable>> rows;
    for (const Variable& v : model.variables())
        if (v.version == 0 || v.version == model.fmiVersion()) rows.push_back(std::cref(v));
    return rows;
}

// The causality/variability/initial attributes of a table row; outputs are continuous Reals
// or discrete counters.
std::string causalityAttributes(const Variable& v) {
    switch (v.causality) {
        case Causality::Parameter: return " causality=\"parameter\" variability=\"fixed\" initial=\"exact\"";
        case Causality::Input: return " causality=\"input\" variability=\"continuous\"";
        case Causality::Output:
            return std::string(" causality=\"output\" variability=\"") +
                   (v.type == VariableType::Real ? "continuous" : "discrete") + "\" initial=\"calculated\"";
    }
    return "";
}

// FMI 3.0: the outputs can be read inside the intermediate update callback, and the inputs that
// take intermediate values set there (Model::takesIntermediateValue).
const char* intermediate(const fmu::Model& model, Causality causality) {
    return model.providesIntermediateUpdate() && causality == Causality::Output ? " intermediateUpdate=\"true\"" : "";
}
const char* intermediate(const fmu::Model& model, const Variable& v) {
    return model.providesIntermediateUpdate() && model.takesIntermediateValue(v) ? " intermediateUpdate=\"true\""
                                                                                 : intermediate(model, v.causality);
}

std::string rangeAndStart(const fmu::Model& model, const Variable& v) {
    std::string text;
    if (v.unit) text += " unit=\"" + escape(v.unit) + "\"";
    if (!std::isnan(v.min)) text += " min=\"" + startText(v, v.min) + "\"";
    if (!std::isnan(v.max)) text += " max=\"" + startText(v, v.max) + "\"";
    if (v.causality != Causality::Output) text += " start=\"" + startText(v, model.get(v)) + "\"";
    return text;
}

class Fmi2Emitter final : public Emitter {
public:
    Fmi2Emitter() : Emitter(2) {}
    const char* typeName(VariableType type) const override { return fmu::typeName(type); }

    void header(std::ostream& xml, const fmu::Model& model) const override {
        const fmu::ModelInfo& info = model.info();
        xml << "  guid=\"" << fmu::modelGuid() << "\"\n  numberOfEventIndicators=\"0\">\n\n";
        const char* states = boolText(info.canGetAndSetFMUstate);
        xml << "  <CoSimulation\n    modelIdentifier=\"" << info.modelIdentifier << "\"\n"
            << "    needsExecutionTool=\"false\"\n    canHandleVariableCommunicationStepSize=\"true\"\n"
            << "    canInterpolateInputs=\"" << boolText(info.canInterpolateInputs) << "\"\n"
            << "    maxOutputDerivativeOrder=\"" << info.maxOutputDerivativeOrder << "\"\n"
            << "    canRunAsynchronuously=\"false\"\n    canBeInstantiatedOnlyOncePerProcess=\"false\"\n"
            << "    canNotUseMemoryManagementFunctions=\"true\"\n    canGetAndSetFMUstate=\"" << states << "\"\n"
            << "    canSerializeFMUstate=\"" << states << "\"\n    providesDirectionalDerivative=\"false\"/>\n\n";
    }

    void variables(std::ostream& xml, const fmu::Model& model) const override {
        const auto variables = rowsOf(model);
        xml << "  <ModelVariables>\n";
        std::vector<std::size_t> outputs;
        for (std::size_t i = 0; i < variables.size(); ++i) {
            const Variable& v = variables[i];
            if (v.causality == Causality::Output) outputs.push_back(i + 1);
            xml << "    <!-- index " << i + 1 << " --><ScalarVariable name=\"" << v.name << "\" valueReference=\""
                << v.vr << "\"" << causalityAttributes(v) << " description=\"" << escape(describe(v, version))
                << "\">\n      <" << typeName(v.type) << rangeAndStart(model, v) << "/></ScalarVariable>\n";
        }
        xml << "  </ModelVariables>\n\n";
        // No direct feedthrough: the outputs at a communication point depend on the inputs only
        // through the steps before it.
        xml << "  <ModelStructure>\n    <Outputs>\n";
        for (std::size_t index : outputs) xml << "      <Unknown index=\"" << index << "\" dependencies=\"\"/>\n";
        xml << "    </Outputs>\n    <InitialUnknowns>\n";
        for (std::size_t index : outputs) xml << "      <Unknown index=\"" << index << "\"/>\n";
        xml << "    </InitialUnknowns>\n  </ModelStructure>\n\n";
    }
};

class Fmi3Emitter final : public Emitter {
public:
    Fmi3Emitter() : Emitter(3) {}
    const char* typeName(VariableType type) const override { return fmu::fmi3::typeName(type); }

    void header(std::ostream& xml, const fmu::Model& model) const override {
        const fmu::ModelInfo& info = model.info();
        xml << "  instantiationToken=\"" << fmu::modelGuid() << "\">\n\n";
        const char* states = boolText(info.canGetAndSetFMUstate);
        xml << "  <CoSimulation\n    modelIdentifier=\"" << info.modelIdentifier << "\"\n"
            << "    needsExecutionTool=\"false\"\n    canBeInstantiatedOnlyOncePerProcess=\"false\"\n"
            << "    canGetAndSetFMUState=\"" << states << "\"\n    canSerializeFMUState=\"" << states << "\"\n"
            << "    providesDirectionalDerivatives=\"false\"\n    providesAdjointDerivatives=\"false\"\n"
            << "    canHandleVariableCommunicationStepSize=\"true\"\n";
        if (model.fixedInternalStepSize() > 0)
            xml << "    fixedInternalStepSize=\"" << real(model.fixedInternalStepSize()) << "\"\n";
        xml << "    maxOutputDerivativeOrder=\"" << info.maxOutputDerivativeOrder << "\"\n"
            << "    providesIntermediateUpdate=\"" << boolText(model.providesIntermediateUpdate())
            << "\"\n    mightReturnEarlyFromDoStep=\"" << boolText(model.hasEvents())
            << "\"\n    hasEventMode=\"true\"/>\n\n";
    }

    void variables(std::ostream& xml, const fmu::Model& model) const override {
        xml << "  <ModelVariables>\n"
            << "    <Float64 name=\"time\" valueReference=\"" << fmu::fmi3::kTimeValueReference
            << "\" causality=\"independent\" variability=\"continuous\" description=\"Simulation time\"/>\n";
        std::vector<fmu::ValueReference> outputs;
        for (const Variable& v : rowsOf(model)) {
            if (v.causality == Causality::Output) outputs.push_back(v.vr);
            xml << "    <" << typeName(v.type) << " name=\"" << v.name << "\" valueReference=\"" << v.vr << "\""
                << causalityAttributes(v) << intermediate(model, v) << rangeAndStart(model, v) << " description=\""
                << escape(describe(v, version)) << "\"/>\n";
        }
        for (const fmu::StructuralParameter& s : model.structuralParameters()) {
            xml << "    <UInt64 name=\"" << s.name << "\" valueReference=\"" << s.vr
                << "\" causality=\"structuralParameter\" variability=\"fixed\" initial=\"exact\" start=\""
                << structuralStart(model, s) << "\"";
            if (s.ownValue()) xml << " min=\"" << s.min << "\" max=\"" << s.max << "\"";
            xml << " description=\"" << escape(forVersion(s.description, version)) << "\"/>\n";
        }
        for (const fmu::ArrayVariable& a : model.arrayVariables()) {
            xml << "    <Float64 name=\"" << a.name << "\" valueReference=\"" << a.vr << "\"";
            if (a.causality == Causality::Parameter)
                xml << " causality=\"parameter\" variability=\"fixed\" initial=\"exact\"";
            else
                xml << " causality=\"output\" variability=\"continuous\" initial=\"calculated\""
                    << intermediate(model, Causality::Output);
            if (a.unit) xml << " unit=\"" << escape(a.unit) << "\"";
            if (!std::isnan(a.min)) xml << " min=\"" << real(a.min) << "\"";
            if (!std::isnan(a.max)) xml << " max=\"" << real(a.max) << "\"";
            if (a.causality == Causality::Parameter) xml << " start=\"" << arrayStart(model, a) << "\"";
            xml << " description=\"" << escape(forVersion(a.description, version)) << "\">\n";
            for (fmu::ValueReference extent : a.extents)
                xml << "      <Dimension valueReference=\"" << extent << "\"/>\n";
            xml << "    </Float64>\n";
            if (a.causality == Causality::Output) outputs.push_back(a.vr);
        }
        xml << "  </ModelVariables>\n\n";
        // No direct feedthrough: the outputs at a communication point depend on the inputs only
        // through the steps before it.
        xml << "  <ModelStructure>\n";
        for (fmu::ValueReference vr : outputs)
            xml << "    <Output valueReference=\"" << vr << "\" dependencies=\"\"/>\n";
        for (fmu::ValueReference vr : outputs) xml << "    <InitialUnknown valueReference=\"" << vr << "\"/>\n";
        xml << "  </ModelStructure>\n\n";
    }

    void extraRows(std::ostream& html, const fmu::Model& model) const override {
        html << "<tr><td><code>time</code></td><td>" << fmu::fmi3::kTimeValueReference
             << "</td><td>independent</td><td>Float64</td><td></td><td></td><td></td><td>s</td><td>Simulation "
                "time</td></tr>\n";
        for (const fmu::StructuralParameter& s : model.structuralParameters())
            html << "<tr><td><code>" << s.name << "</code></td><td>" << s.vr
                 << "</td><td>structuralParameter</td><td>UInt64</td><td>" << structuralStart(model, s) << "</td><td>"
                 << (s.ownValue() ? std::to_string(s.min) : "") << "</td><td>"
                 << (s.ownValue() ? std::to_string(s.max) : "") << "</td><td></td><td>"
                 << escape(forVersion(s.description, version)) << "</td></tr>\n";
        for (const fmu::ArrayVariable& a : model.arrayVariables()) {
            html << "<tr><td><code>" << a.name << "</code></td><td>" << a.vr << "</td><td>"
                 << (a.causality == Causality::Parameter ? "parameter" : "output") << "</td><td>Float64[";
            for (std::size_t k = 0; k < a.extents.size(); ++k) {
                const fmu::StructuralParameter* s = model.findStructural(a.extents[k]);
                html << (k ? "][" : "") << (s ? s->name : "?");
            }
            html << "]</td><td>" << (a.causality == Causality::Parameter ? arrayStart(model, a) : "") << "</td><td>"
                 << (std::isnan(a.min) ? "" : real(a.min)) << "</td><td>" << (std::isnan(a.max) ? "" : real(a.max))
                 << "</td><td>" << (a.unit ? escape(a.unit) : "") << "</td><td>"
                 << escape(forVersion(a.description, version)) << "</td></tr>\n";
        }
    }

private:
    // A parameter array's start values, space-separated (as many as its extents' starts give).
    static std::string arrayStart(const fmu::Model& model, const fmu::ArrayVariable& a) {
        std::size_t n = 1;
        for (fmu::ValueReference extent : a.extents) {
            const fmu::StructuralParameter* s = model.findStructural(extent);
            if (!s) throw std::runtime_error(std::string(a.name) + ": an extent is no structural parameter");
            n *= std::size_t(structuralStart(model, *s));
        }
        std::vector<double> values(n);
        model.getArray(a, values.data(), n);
        std::string text;
        for (double x : values) text += (text.empty() ? "" : " ") + real(x);
        return text;
    }
    static long long structuralStart(const fmu::Model& model, const fmu::StructuralParameter& s) {
        if (s.ownValue()) return s.offset;
        const Variable* base = model.find(s.parameter);
        if (!base) throw std::runtime_error(std::string(s.name) + " is a view of no parameter of the table");
        return static_cast<long long>(model.get(*base)) + s.offset;
    }
};

void writeDescription(std::ostream& xml, const fmu::Model& model, const Emitter& emitter,
                      const std::vector<License>& licenses) {
    const fmu::ModelInfo& info = model.info();
    const char* version = PLATEIMPACT_VERSION;
    xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        << "<!-- Generated at build time from the table of variables of the model binding\n"
        << "     (modelDescription/WriteModelDescription.cpp): do not edit. -->\n"
        << "<fmiModelDescription\n  fmiVersion=\"" << emitter.version << ".0\"\n  modelName=\"" << info.modelName
        << "\"\n  description=\"" << escape(forVersion(info.description, emitter.version)) << "\"\n  author=\""
        << escape(PLATEIMPACT_AUTHOR) << "\"\n  version=\"" << version << "\"\n  copyright=\""
        << escape(PLATEIMPACT_COPYRIGHT) << "\"\n  license=\"" << escape(licenseText(licenses))
        << "\"\n  generationTool=\"PlateImpact " << version << " (CMake)\"\n  generationDateAndTime=\""
        << generationDateAndTime() << "\"\n  variableNamingConvention=\"flat\"\n";
    emitter.header(xml, model);

    std::vector<std::string> units;
    const auto addUnit = [&](const char* unit) {
        if (unit && std::find(units.begin(), units.end(), unit) == units.end()) units.push_back(unit);
    };
    for (const Variable& v : model.variables()) addUnit(v.unit);
    if (emitter.version == 3)
        for (const fmu::ArrayVariable& a : model.arrayVariables()) addUnit(a.unit);
    if (!units.empty()) {
        xml << "  <UnitDefinitions>\n";
        for (const std::string& unit : units) {
            const std::string base = description::baseUnit(unit);
            xml << "    <Unit name=\"" << escape(unit) << "\"><BaseUnit" << (base.empty() ? "" : " ") << base
                << "/></Unit>\n";
        }
        xml << "  </UnitDefinitions>\n\n";
    }

    // Every category fmu::Instance logs under (fmu/core/Instance.h, LogCategory).
    const std::string v = std::to_string(emitter.version);
    xml << "  <LogCategories>\n"
        << "    <Category name=\"logStatusError\" description=\"Messages explaining an fmi" << v << "Error or fmi" << v
        << "Discard return (on unless switched off)\"/>\n"
        << "    <Category name=\"logStatusWarning\" description=\"Warnings (on when loggingOn)\"/>\n"
        << "    <Category name=\"logInfo\" description=\"What an initialization will cost (memory, time, before it "
           "is spent) and its progress (on when loggingOn)\"/>\n"
        << "    <Category name=\"logAll\" description=\"Trace of the FMU's work: instantiation, builds, steps"
        << (emitter.version == 3 ? ", early returns" : "") << "; setting this category switches all categories\"/>\n"
        << "  </LogCategories>\n\n";

    xml << "  <DefaultExperiment startTime=\"0\" stopTime=\"" << real(info.defaultStopTime) << "\" stepSize=\""
        << real(info.defaultStepSize) << "\"/>\n\n";
    emitter.variables(xml, model);
    xml << "</fmiModelDescription>\n";
}

// documentation/index.html (FMI 2.0 section 2.4, FMI 3.0 section 2.5): the model's own page for
// this version, the table of variables the XML declares, the licences of what the FMU contains.
void writeDocumentation(std::ostream& html, const fmu::Model& model, const Emitter& emitter,
                        const std::vector<License>& licenses) {
    const fmu::ModelInfo& info = model.info();
    const int version = emitter.version;
    html << "<!DOCTYPE html>\n<html lang=\"en\">\n<head><meta charset=\"utf-8\"><title>" << info.modelName
         << "</title>\n<style>body{font-family:sans-serif;max-width:60em;margin:2em auto;line-height:1.4}"
            "table{border-collapse:collapse}td,th{border:1px solid #bbb;padding:.2em .5em;vertical-align:top}"
            "</style></head>\n<body>\n<h1>"
         << info.modelName << " (FMI " << version << ".0 Co-Simulation, version " << PLATEIMPACT_VERSION
         << ")</h1>\n<p>" << escape(forVersion(info.description, version)) << "</p>\n";
    if (info.documentationHtml) html << forVersion(info.documentationHtml, version);
    html << "<h2>Variables</h2>\n<table>\n<tr><th>name</th><th>value reference</th><th>causality</th><th>type</th>"
            "<th>start</th><th>min</th><th>max</th><th>unit</th><th>description</th></tr>\n";
    emitter.extraRows(html, model);
    for (const Variable& v : rowsOf(model)) {
        const char* causality = v.causality == Causality::Parameter ? "parameter"
                                : v.causality == Causality::Input   ? "input"
                                                                    : "output";
        html << "<tr><td><code>" << v.name << "</code></td><td>" << v.vr << "</td><td>" << causality << "</td><td>"
             << emitter.typeName(v.type) << "</td><td>"
             << (v.causality == Causality::Output ? "" : escape(startText(v, model.get(v)))) << "</td><td>"
             << (std::isnan(v.min) ? "" : startText(v, v.min)) << "</td><td>"
             << (std::isnan(v.max) ? "" : startText(v, v.max)) << "</td><td>" << (v.unit ? escape(v.unit) : "")
             << "</td><td>" << escape(describe(v, version));
        if (v.enumeration) {
            html << "<ul>";
            for (const fmu::EnumerationItem& item : v.enumeration->items)
                html << "<li>" << item.value << " = <code>" << item.name << "</code>: " << escape(item.description)
                     << "</li>";
            html << "</ul>";
        }
        html << "</td></tr>\n";
    }
    html << "</table>\n<h2>Licences</h2>\n<p>" << info.modelName << " is licensed under " << PLATEIMPACT_LICENSE << " ("
         << escape(PLATEIMPACT_COPYRIGHT) << "). The licence texts of what this FMU's binaries contain are in "
         << "<code>licenses/</code>:</p>\n<ul>\n";
    for (const License& l : licenses)
        html << "<li><code>licenses/" << escape(l.name) << ".txt</code>: " << escape(l.name) << ", " << escape(l.spdx)
             << "</li>\n";
    html << "</ul>\n</body>\n</html>\n";
}

// terminalsAndIcons/terminalsAndIcons.xml (FMI 3.0 section 2.4.9): the model's terminals, each
// member checked against the table (a terminal cannot name a variable the FMU does not have).
void writeTerminals(std::ostream& xml, const fmu::Model& model) {
    xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        << "<!-- Generated at build time from the model binding's terminals\n"
        << "     (modelDescription/WriteModelDescription.cpp): do not edit. -->\n"
        << "<fmiTerminalsAndIcons fmiVersion=\"3.0\">\n  <Terminals>\n";
    for (const fmu::Terminal& t : model.terminals()) {
        xml << "    <Terminal name=\"" << escape(t.name) << "\" matchingRule=\"" << escape(t.matchingRule)
            << "\" terminalKind=\"" << escape(t.terminalKind) << "\" description=\"" << escape(t.description)
            << "\">\n";
        for (const fmu::TerminalMember& m : t.members) {
            const auto rows = rowsOf(model);
            const bool known = std::any_of(rows.begin(), rows.end(),
                                           [&](const Variable& v) { return std::string(v.name) == m.variableName; });
            if (!known) throw std::runtime_error(std::string("terminal ") + t.name + ": no variable " + m.variableName);
            xml << "      <TerminalMemberVariable variableName=\"" << escape(m.variableName) << "\" memberName=\""
                << escape(m.memberName) << "\" variableKind=\"" << escape(m.variableKind) << "\"/>\n";
        }
        xml << "    </Terminal>\n";
    }
    xml << "  </Terminals>\n</fmiTerminalsAndIcons>\n";
}

}  // namespace

int main(int argc, char** argv) {
    const std::string versionArg = argc > 1 ? argv[1] : "";
    if (argc < 4 || (versionArg != "2" && versionArg != "3")) {
        std::cerr << "usage: " << argv[0]
                  << " <2|3> <modelDescription.xml> <documentation/index.html> [--terminals=<terminalsAndIcons.xml>] "
                     "[<name>:<SPDX>:<path> ...]\n";
        return 2;
    }
    try {
        std::vector<License> licenses;
        std::string terminals;  // --terminals=<path>: FMI 3.0 terminalsAndIcons.xml
        for (int k = 4; k < argc; ++k) {
            const std::string arg = argv[k];
            if (arg.rfind("--terminals=", 0) == 0)
                terminals = arg.substr(12);
            else
                licenses.push_back(parseLicense(arg));
        }
        std::unique_ptr<Emitter> emitter;
        if (versionArg == "2")
            emitter = std::make_unique<Fmi2Emitter>();
        else
            emitter = std::make_unique<Fmi3Emitter>();
        const std::unique_ptr<fmu::Model> model = fmu::createModel();
        model->useVersion(emitter->version);
        std::ofstream xml(argv[2]);
        writeDescription(xml, *model, *emitter, licenses);
        if (!xml) throw std::runtime_error(std::string("cannot write ") + argv[2]);
        std::ofstream html(argv[3]);
        writeDocumentation(html, *model, *emitter, licenses);
        if (!html) throw std::runtime_error(std::string("cannot write ") + argv[3]);
        if (!terminals.empty()) {
            if (versionArg != "3") throw std::runtime_error("terminals are FMI 3.0 only");
            std::remove(terminals.c_str());  // a model without terminals writes none
            if (model->terminals().empty()) return 0;
            std::ofstream out(terminals);
            writeTerminals(out, *model);
            if (!out) throw std::runtime_error("cannot write " + terminals);
        }
    } catch (const std::exception& e) {
        std::cerr << argv[0] << ": " << e.what() << "\n";
        return 1;
    }
    return 0;
}
