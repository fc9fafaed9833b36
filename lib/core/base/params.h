// SPDX-License-Identifier: Apache-2.0
// Named parameters: one descriptor table per filter type drives validation, the C API's
// introspection, `afntool --help` and the plugin's parameters (no hand-kept copies).
#pragma once

#include "afn/afn.h"

#include <map>
#include <string>
#include <vector>

namespace afn {

/// One parameter: name, type, default, range or choices, label and help (units, source).
struct ParamDesc {
    std::string name;
    AFNParamType type = AFN_PARAM_FLOAT;
    double defaultValue = 0.0;
    double minValue = 0.0;
    double maxValue = 0.0;
    std::string defaultString;
    std::string choices; ///< '|'-separated (strings only)
    std::string label;
    std::string help;
};

/// Convenience constructors for descriptor tables.
ParamDesc boolParam(std::string name, bool def, std::string label, std::string help);
ParamDesc intParam(std::string name, int def, int lo, int hi, std::string label, std::string help);
ParamDesc floatParam(std::string name, double def, double lo, double hi, std::string label,
                     std::string help);
ParamDesc choiceParam(std::string name, std::string def, std::string choices, std::string label,
                      std::string help);

/// Parameter values of one filter, validated against its descriptor table.
class ParamSet {
public:
    explicit ParamSet(const std::vector<ParamDesc>* table = nullptr);

    const ParamDesc& desc(const std::string& name) const; ///< throws InvalidArgument if unknown
    bool has(const std::string& name) const;

    void setNumber(const std::string& name, double value, AFNParamType givenType);
    void setString(const std::string& name, const std::string& value);

    bool getBool(const std::string& name) const { return getNumber(name) != 0.0; }
    int getInt(const std::string& name) const { return static_cast<int>(getNumber(name)); }
    float getFloat(const std::string& name) const { return static_cast<float>(getNumber(name)); }
    double getNumber(const std::string& name) const;
    const std::string& getString(const std::string& name) const;

    const std::vector<ParamDesc>& table() const { return *m_table; }

private:
    const std::vector<ParamDesc>* m_table;
    std::map<std::string, double> m_numbers;
    std::map<std::string, std::string> m_strings;
};

/// Split a '|'-separated choice list.
std::vector<std::string> splitChoices(const std::string& choices);

} // namespace afn
