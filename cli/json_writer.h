// SPDX-License-Identifier: Apache-2.0
// A minimal streaming JSON writer (objects, arrays, strings, numbers) for machine-readable output.
#pragma once

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace afntool {

class JsonWriter {
public:
    std::string str() const { return m_out.str(); }

    JsonWriter& beginObject() { return open('{'); }
    JsonWriter& endObject() { return close('}'); }
    JsonWriter& beginArray() { return open('['); }
    JsonWriter& endArray() { return close(']'); }
    /// Write an object key; the next value belongs to it.
    JsonWriter& key(const std::string& k)
    {
        separate();
        m_out << quote(k) << ": ";
        m_afterKey = true;
        return *this;
    }
    JsonWriter& value(const std::string& s) { return raw(quote(s)); }
    JsonWriter& value(const char* s) { return raw(quote(s)); }
    JsonWriter& value(bool b) { return raw(b ? "true" : "false"); }
    JsonWriter& null() { return raw("null"); }
    JsonWriter& value(long long v) { return raw(std::to_string(v)); }
    JsonWriter& value(int v) { return raw(std::to_string(v)); }
    JsonWriter& value(double v)
    {
        if (!std::isfinite(v))
            return raw("null");
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.9g", v);
        return raw(buf);
    }
    JsonWriter& value(const std::vector<std::string>& list)
    {
        beginArray();
        for (const auto& s : list)
            value(s);
        return endArray();
    }
    template <typename T> JsonWriter& field(const std::string& k, const T& v)
    {
        return key(k).value(v);
    }

    static std::string quote(const std::string& s)
    {
        std::string o = "\"";
        for (unsigned char c : s) {
            switch (c) {
            case '"':
                o += "\\\"";
                break;
            case '\\':
                o += "\\\\";
                break;
            case '\n':
                o += "\\n";
                break;
            case '\t':
                o += "\\t";
                break;
            case '\r':
                o += "\\r";
                break;
            default:
                if (c < 0x20) {
                    char buf[8];
                    std::snprintf(buf, sizeof buf, "\\u%04x", c);
                    o += buf;
                } else {
                    o += static_cast<char>(c);
                }
            }
        }
        return o + "\"";
    }

private:
    JsonWriter& open(char c)
    {
        separate();
        m_out << c;
        m_first.push_back(true);
        return *this;
    }
    JsonWriter& close(char c)
    {
        m_first.pop_back();
        m_out << c;
        return *this;
    }
    JsonWriter& raw(const std::string& s)
    {
        separate();
        m_out << s;
        return *this;
    }
    void separate()
    {
        if (m_afterKey) {
            m_afterKey = false;
            return;
        }
        if (!m_first.empty()) {
            if (!m_first.back())
                m_out << ", ";
            m_first.back() = false;
        }
    }

    std::ostringstream m_out;
    std::vector<bool> m_first;
    bool m_afterKey = false;
};

} // namespace afntool
