// SPDX-License-Identifier: Apache-2.0
// The test host's property suite: typed arrays, strict about types as real hosts are.
#include "ofx_test_host.h"

#include <stdexcept>

using ofxhost::Prop;

void OfxPropertySetStruct::setInts(const std::string& name, std::vector<int> v)
{
    Prop& p = props[name];
    p.type = Prop::Int;
    p.i = std::move(v);
}

void OfxPropertySetStruct::setDoubles(const std::string& name, std::vector<double> v)
{
    Prop& p = props[name];
    p.type = Prop::Double;
    p.d = std::move(v);
}

void OfxPropertySetStruct::setStrings(const std::string& name, std::vector<std::string> v)
{
    Prop& p = props[name];
    p.type = Prop::String;
    p.s = std::move(v);
}

void OfxPropertySetStruct::setPointer(const std::string& name, void* v)
{
    Prop& p = props[name];
    p.type = Prop::Pointer;
    p.p = { v };
}

int OfxPropertySetStruct::getInt(const std::string& name, int index) const
{
    return props.at(name).i.at(index);
}

double OfxPropertySetStruct::getDouble(const std::string& name, int index) const
{
    return props.at(name).d.at(index);
}

const std::string& OfxPropertySetStruct::getString(const std::string& name, int index) const
{
    return props.at(name).s.at(index);
}

const std::vector<std::string>& OfxPropertySetStruct::getStrings(const std::string& name) const
{
    return props.at(name).s;
}

void* OfxPropertySetStruct::getPointer(const std::string& name, int index) const
{
    return props.at(name).p.at(index);
}

namespace {

template <typename T> std::vector<T>& values(Prop& p);
template <> std::vector<int>& values<int>(Prop& p)
{
    return p.i;
}
template <> std::vector<double>& values<double>(Prop& p)
{
    return p.d;
}
template <> std::vector<std::string>& values<std::string>(Prop& p)
{
    return p.s;
}
template <> std::vector<void*>& values<void*>(Prop& p)
{
    return p.p;
}

template <typename T>
OfxStatus setOne(OfxPropertySetHandle h, const char* name, int index, Prop::Type type, const T& v)
{
    if (!h || !name || index < 0)
        return kOfxStatErrBadHandle;
    auto it = h->props.find(name);
    if (it == h->props.end()) {
        Prop p;
        p.type = type;
        it = h->props.emplace(name, std::move(p)).first;
    } else if (it->second.type != type) {
        return kOfxStatErrValue;
    }
    std::vector<T>& vec = values<T>(it->second);
    if (static_cast<size_t>(index) >= vec.size())
        vec.resize(index + 1);
    vec[index] = v;
    return kOfxStatOK;
}

template <typename T>
OfxStatus getOne(OfxPropertySetHandle h, const char* name, int index, Prop::Type type, T* out)
{
    if (!h || !name || !out)
        return kOfxStatErrBadHandle;
    auto it = h->props.find(name);
    if (it == h->props.end())
        return kOfxStatErrUnknown;
    if (it->second.type != type)
        return kOfxStatErrValue;
    std::vector<T>& vec = values<T>(it->second);
    if (index < 0 || static_cast<size_t>(index) >= vec.size())
        return kOfxStatErrBadIndex;
    *out = vec[index];
    return kOfxStatOK;
}

OfxStatus setPointer(OfxPropertySetHandle h, const char* n, int i, void* v)
{
    return setOne<void*>(h, n, i, Prop::Pointer, v);
}
OfxStatus setString(OfxPropertySetHandle h, const char* n, int i, const char* v)
{
    return setOne<std::string>(h, n, i, Prop::String, v ? v : "");
}
OfxStatus setDouble(OfxPropertySetHandle h, const char* n, int i, double v)
{
    return setOne<double>(h, n, i, Prop::Double, v);
}
OfxStatus setInt(OfxPropertySetHandle h, const char* n, int i, int v)
{
    return setOne<int>(h, n, i, Prop::Int, v);
}
OfxStatus setPointerN(OfxPropertySetHandle h, const char* n, int c, void* const* v)
{
    for (int i = 0; i < c; ++i)
        if (OfxStatus s = setPointer(h, n, i, v[i]))
            return s;
    return kOfxStatOK;
}
OfxStatus setStringN(OfxPropertySetHandle h, const char* n, int c, const char* const* v)
{
    for (int i = 0; i < c; ++i)
        if (OfxStatus s = setString(h, n, i, v[i]))
            return s;
    return kOfxStatOK;
}
OfxStatus setDoubleN(OfxPropertySetHandle h, const char* n, int c, const double* v)
{
    for (int i = 0; i < c; ++i)
        if (OfxStatus s = setDouble(h, n, i, v[i]))
            return s;
    return kOfxStatOK;
}
OfxStatus setIntN(OfxPropertySetHandle h, const char* n, int c, const int* v)
{
    for (int i = 0; i < c; ++i)
        if (OfxStatus s = setInt(h, n, i, v[i]))
            return s;
    return kOfxStatOK;
}
OfxStatus getPointer(OfxPropertySetHandle h, const char* n, int i, void** v)
{
    return getOne<void*>(h, n, i, Prop::Pointer, v);
}
OfxStatus getString(OfxPropertySetHandle h, const char* n, int i, char** v)
{
    if (!h || !n || !v)
        return kOfxStatErrBadHandle;
    auto it = h->props.find(n);
    if (it == h->props.end())
        return kOfxStatErrUnknown;
    if (it->second.type != Prop::String)
        return kOfxStatErrValue;
    if (i < 0 || static_cast<size_t>(i) >= it->second.s.size())
        return kOfxStatErrBadIndex;
    *v = const_cast<char*>(it->second.s[i].c_str());
    return kOfxStatOK;
}
OfxStatus getDouble(OfxPropertySetHandle h, const char* n, int i, double* v)
{
    return getOne<double>(h, n, i, Prop::Double, v);
}
OfxStatus getInt(OfxPropertySetHandle h, const char* n, int i, int* v)
{
    return getOne<int>(h, n, i, Prop::Int, v);
}
OfxStatus getPointerN(OfxPropertySetHandle h, const char* n, int c, void** v)
{
    for (int i = 0; i < c; ++i)
        if (OfxStatus s = getPointer(h, n, i, v + i))
            return s;
    return kOfxStatOK;
}
OfxStatus getStringN(OfxPropertySetHandle h, const char* n, int c, char** v)
{
    for (int i = 0; i < c; ++i)
        if (OfxStatus s = getString(h, n, i, v + i))
            return s;
    return kOfxStatOK;
}
OfxStatus getDoubleN(OfxPropertySetHandle h, const char* n, int c, double* v)
{
    for (int i = 0; i < c; ++i)
        if (OfxStatus s = getDouble(h, n, i, v + i))
            return s;
    return kOfxStatOK;
}
OfxStatus getIntN(OfxPropertySetHandle h, const char* n, int c, int* v)
{
    for (int i = 0; i < c; ++i)
        if (OfxStatus s = getInt(h, n, i, v + i))
            return s;
    return kOfxStatOK;
}
OfxStatus reset(OfxPropertySetHandle h, const char* n)
{
    if (!h || !n)
        return kOfxStatErrBadHandle;
    return h->props.erase(n) ? kOfxStatOK : kOfxStatErrUnknown;
}
OfxStatus dimension(OfxPropertySetHandle h, const char* n, int* count)
{
    if (!h || !n || !count)
        return kOfxStatErrBadHandle;
    auto it = h->props.find(n);
    if (it == h->props.end())
        return kOfxStatErrUnknown;
    const Prop& p = it->second;
    *count = int(p.type == Prop::Int ? p.i.size()
            : p.type == Prop::Double ? p.d.size()
            : p.type == Prop::String ? p.s.size()
                                     : p.p.size());
    return kOfxStatOK;
}

} // namespace

namespace ofxhost {

const OfxPropertySuiteV1* propertySuite()
{
    static const OfxPropertySuiteV1 suite = {
        setPointer,
        setString,
        setDouble,
        setInt,
        setPointerN,
        setStringN,
        setDoubleN,
        setIntN,
        getPointer,
        getString,
        getDouble,
        getInt,
        getPointerN,
        getStringN,
        getDoubleN,
        getIntN,
        reset,
        dimension,
    };
    return &suite;
}

} // namespace ofxhost
