// SPDX-License-Identifier: Apache-2.0
// Named parameters. A settings struct is the one source of every default; a ParamBinding ties each
// of its members to a descriptor (name, range or choices, label, help). The descriptors drive
// validation, the C API's introspection, `afntool --help` and the plugin's parameters; reading a
// committed ParamSet back into the struct goes through the same binding, so a parameter is
// written once: a member with its default, and one add() line.
#pragma once

#include "afn/afn.h"
#include "base/exception.h"

#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <string>
#include <utility>
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
    std::vector<std::string> choiceList; ///< accepted strings (AFN_PARAM_STRING only)
    std::string choices; ///< the same, '|'-separated (the C API's form)
    std::string label;
    std::string help;
};

/// Parameter values of one filter, validated against its descriptor table.
class ParamSet {
public:
    explicit ParamSet(const std::vector<ParamDesc>* table = nullptr);

    const ParamDesc& desc(const std::string& name) const; ///< throws InvalidArgument if unknown
    bool has(const std::string& name) const;

    void setNumber(const std::string& name, double value, AFNParamType givenType);
    void setString(const std::string& name, const std::string& value);

    double getNumber(const std::string& name) const;
    const std::string& getString(const std::string& name) const;

    const std::vector<ParamDesc>& table() const { return *m_table; }

private:
    const std::vector<ParamDesc>* m_table;
    std::map<std::string, double> m_numbers;
    std::map<std::string, std::string> m_strings;
};

/// Descriptors bound to the members of a settings struct S (defaults = S's member initialisers).
template <typename S> class ParamBinding {
public:
    /// A float member in [lo, hi].
    ParamBinding& add(float S::*member, const char* name, double lo, double hi, const char* label,
        const char* help)
    {
        return number(member, AFN_PARAM_FLOAT, name, lo, hi, label, help);
    }
    /// An integer member in [lo, hi].
    ParamBinding& add(
        int S::*member, const char* name, int lo, int hi, const char* label, const char* help)
    {
        return number(member, AFN_PARAM_INT, name, lo, hi, label, help);
    }
    /// A bool member.
    ParamBinding& add(bool S::*member, const char* name, const char* label, const char* help)
    {
        return number(member, AFN_PARAM_BOOL, name, 0.0, 1.0, label, help);
    }
    /// An enum member chosen by name: `choices` lists every (name, value) in display order.
    template <typename E>
    ParamBinding& add(E S::*member, const char* name,
        std::vector<std::pair<const char*, E>> choices, const char* label, const char* help)
    {
        ParamDesc d = describe(AFN_PARAM_STRING, name, label, help);
        const E def = S {}.*member;
        for (const auto& [text, value] : choices) {
            d.choiceList.emplace_back(text);
            d.choices += (d.choices.empty() ? "" : "|") + std::string(text);
            if (value == def)
                d.defaultString = text;
        }
        m_entries.push_back({ std::move(d), [member, name, choices](const ParamSet& p, S& s) {
                                 const std::string& v = p.getString(name);
                                 for (const auto& [text, value] : choices)
                                     if (v == text)
                                         s.*member = value;
                             } });
        return *this;
    }

    /// The descriptors, in add() order.
    std::vector<ParamDesc> descriptors() const
    {
        std::vector<ParamDesc> out;
        for (const Entry& e : m_entries)
            out.push_back(e.desc);
        return out;
    }
    /// The settings a parameter set holds (members without a descriptor keep their defaults).
    S read(const ParamSet& params) const
    {
        S s {};
        for (const Entry& e : m_entries)
            e.read(params, s);
        return s;
    }

private:
    struct Entry {
        ParamDesc desc;
        std::function<void(const ParamSet&, S&)> read;
    };

    /// The shortest decimal that converts back to `v` at the member's precision (a float
    /// member's 0.2f is described as 0.2, not 0.20000000298).
    static double shortestDecimal(double v, std::size_t bytes)
    {
        if (bytes != sizeof(float))
            return v;
        for (int digits = 1; digits <= 9; ++digits) {
            char text[32];
            std::snprintf(text, sizeof(text), "%.*g", digits, v);
            const double d = std::strtod(text, nullptr);
            if (static_cast<float>(d) == static_cast<float>(v))
                return d;
        }
        return v;
    }
    static ParamDesc describe(
        AFNParamType type, const char* name, const char* label, const char* help)
    {
        ParamDesc d;
        d.name = name;
        d.type = type;
        d.label = label;
        d.help = help;
        return d;
    }
    template <typename T>
    ParamBinding& number(T S::*member, AFNParamType type, const char* name, double lo, double hi,
        const char* label, const char* help)
    {
        ParamDesc d = describe(type, name, label, help);
        d.defaultValue = shortestDecimal(static_cast<double>(S {}.*member), sizeof(T));
        d.minValue = lo;
        d.maxValue = hi;
        m_entries.push_back({ std::move(d), [member, name](const ParamSet& p, S& s) {
                                 s.*member = static_cast<T>(p.getNumber(name));
                             } });
        return *this;
    }

    std::vector<Entry> m_entries;
};

} // namespace afn
