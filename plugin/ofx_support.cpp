// SPDX-License-Identifier: Apache-2.0
#include "ofx_support.h"

namespace afnofx {

Suites& suites()
{
    static Suites s;
    return s;
}

bool fetchSuites()
{
    Suites& s = suites();
    if (!s.host || !s.host->fetchSuite)
        return false;
    auto fetch = [&](const char* name, int version) {
        return s.host->fetchSuite(s.host->host, name, version);
    };
    s.prop = static_cast<const OfxPropertySuiteV1*>(fetch(kOfxPropertySuite, 1));
    s.effect = static_cast<const OfxImageEffectSuiteV1*>(fetch(kOfxImageEffectSuite, 1));
    s.param = static_cast<const OfxParameterSuiteV1*>(fetch(kOfxParameterSuite, 1));
    s.memory = static_cast<const OfxMemorySuiteV1*>(fetch(kOfxMemorySuite, 1));
    s.thread = static_cast<const OfxMultiThreadSuiteV1*>(fetch(kOfxMultiThreadSuite, 1));
    s.message = static_cast<const OfxMessageSuiteV1*>(fetch(kOfxMessageSuite, 1));
    return s.prop && s.effect && s.param;
}

void check(OfxStatus status, const std::string& what)
{
    if (status != kOfxStatOK)
        throw OfxError(status == kOfxStatErrMemory ? kOfxStatErrMemory : kOfxStatFailed,
            what + " failed (OFX status " + std::to_string(status) + ")");
}

static std::string propText(const char* name)
{
    return std::string("property ") + name;
}

int Props::getInt(const char* name, int index) const
{
    int v = 0;
    check(suites().prop->propGetInt(m_handle, name, index, &v), "reading " + propText(name));
    return v;
}

double Props::getDouble(const char* name, int index) const
{
    double v = 0.0;
    check(suites().prop->propGetDouble(m_handle, name, index, &v), "reading " + propText(name));
    return v;
}

std::string Props::getString(const char* name, int index) const
{
    char* v = nullptr;
    check(suites().prop->propGetString(m_handle, name, index, &v), "reading " + propText(name));
    return v ? std::string(v) : std::string();
}

void* Props::getPointer(const char* name, int index) const
{
    void* v = nullptr;
    check(suites().prop->propGetPointer(m_handle, name, index, &v), "reading " + propText(name));
    return v;
}

int Props::getIntOr(const char* name, int fallback) const
{
    int v = 0;
    return suites().prop->propGetInt(m_handle, name, 0, &v) == kOfxStatOK ? v : fallback;
}

int Props::dimension(const char* name) const
{
    int n = 0;
    check(suites().prop->propGetDimension(m_handle, name, &n), "sizing " + propText(name));
    return n;
}

void Props::set(const char* name, int value, int index)
{
    check(suites().prop->propSetInt(m_handle, name, index, value), "setting " + propText(name));
}

void Props::set(const char* name, double value, int index)
{
    check(suites().prop->propSetDouble(m_handle, name, index, value), "setting " + propText(name));
}

void Props::set(const char* name, const char* value, int index)
{
    check(suites().prop->propSetString(m_handle, name, index, value), "setting " + propText(name));
}

void Props::set(const char* name, const std::string& value, int index)
{
    set(name, value.c_str(), index);
}

void Props::setPointer(const char* name, void* value, int index)
{
    check(suites().prop->propSetPointer(m_handle, name, index, value), "setting " + propText(name));
}

void Props::setDoubles(const char* name, const std::vector<double>& values)
{
    for (size_t i = 0; i < values.size(); ++i)
        set(name, values[i], static_cast<int>(i));
}

void Props::setStrings(const char* name, const std::vector<std::string>& values)
{
    for (size_t i = 0; i < values.size(); ++i)
        set(name, values[i], static_cast<int>(i));
}

void Props::trySet(const char* name, int value)
{
    suites().prop->propSetInt(m_handle, name, 0, value);
}

void postError(void* handle, const std::string& message)
{
    if (suites().message && suites().message->message)
        suites().message->message(handle, kOfxMessageError, "", "%s", message.c_str());
}

void postNote(void* handle, const std::string& message)
{
    if (suites().message && suites().message->message)
        suites().message->message(handle, kOfxMessageLog, "", "%s", message.c_str());
}

} // namespace afnofx
