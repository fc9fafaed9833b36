// SPDX-License-Identifier: Apache-2.0
#include "base/params.h"

#include "base/exception.h"

#include <cmath>
#include <sstream>

namespace afn {

static const std::vector<ParamDesc> kEmptyTable;

ParamSet::ParamSet(const std::vector<ParamDesc>* table)
    : m_table(table ? table : &kEmptyTable)
{
    for (const ParamDesc& d : *m_table) {
        if (d.type == AFN_PARAM_STRING)
            m_strings[d.name] = d.defaultString;
        else
            m_numbers[d.name] = d.defaultValue;
    }
}

bool ParamSet::has(const std::string& name) const
{
    for (const ParamDesc& d : *m_table)
        if (d.name == name)
            return true;
    return false;
}

const ParamDesc& ParamSet::desc(const std::string& name) const
{
    for (const ParamDesc& d : *m_table)
        if (d.name == name)
            return d;
    throwInvalidArgument("unknown parameter '" + name + "'");
}

void ParamSet::setNumber(const std::string& name, double value, AFNParamType givenType)
{
    const ParamDesc& d = desc(name);
    if (d.type == AFN_PARAM_STRING)
        throwInvalidArgument("parameter '" + name + "' takes a string (" + d.choices + ")");
    if (d.type == AFN_PARAM_BOOL && givenType == AFN_PARAM_FLOAT)
        throwInvalidArgument("parameter '" + name + "' is a bool");
    if (d.type == AFN_PARAM_INT && givenType == AFN_PARAM_FLOAT && value != std::floor(value))
        throwInvalidArgument("parameter '" + name + "' is an integer");
    if (!std::isfinite(value) || value < d.minValue || value > d.maxValue) {
        std::ostringstream os;
        os << "parameter '" << name << "' = " << value << " is out of range [" << d.minValue << ", "
           << d.maxValue << "]";
        throwInvalidArgument(os.str());
    }
    m_numbers[name] = value;
}

void ParamSet::setString(const std::string& name, const std::string& value)
{
    const ParamDesc& d = desc(name);
    if (d.type != AFN_PARAM_STRING) {
        // Accept numbers written as text (command lines, plugin hosts).
        char* end = nullptr;
        const double v = std::strtod(value.c_str(), &end);
        if (value == "true" || value == "on" || value == "yes")
            return setNumber(name, 1.0, AFN_PARAM_INT);
        if (value == "false" || value == "off" || value == "no")
            return setNumber(name, 0.0, AFN_PARAM_INT);
        if (value.empty() || end == nullptr || *end != '\0')
            throwInvalidArgument("parameter '" + name + "' expects a number, got '" + value + "'");
        return setNumber(name, v, d.type == AFN_PARAM_FLOAT ? AFN_PARAM_FLOAT : AFN_PARAM_INT);
    }
    for (const std::string& c : d.choiceList)
        if (c == value) {
            m_strings[name] = value;
            return;
        }
    throwInvalidArgument("parameter '" + name + "' = '" + value + "' is not one of " + d.choices);
}

double ParamSet::getNumber(const std::string& name) const
{
    auto it = m_numbers.find(name);
    if (it == m_numbers.end())
        throwInvalidArgument("unknown numeric parameter '" + name + "'");
    return it->second;
}

const std::string& ParamSet::getString(const std::string& name) const
{
    auto it = m_strings.find(name);
    if (it == m_strings.end())
        throwInvalidArgument("unknown string parameter '" + name + "'");
    return it->second;
}

} // namespace afn
