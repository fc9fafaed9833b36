// SPDX-License-Identifier: Apache-2.0
// The test host's parameter, memory, multithread and message suites and its suite lookup.
#include "ofx_test_host.h"

#include <cstdarg>
#include <cstdlib>
#include <cstring>
#include <thread>

namespace ofxhost {

const OfxPropertySuiteV1* propertySuite();
const OfxImageEffectSuiteV1* imageEffectSuite();

namespace {

// ---- parameters ---------------------------------------------------------------------------------

bool isIntType(const std::string& t)
{
    return t == kOfxParamTypeInteger || t == kOfxParamTypeBoolean || t == kOfxParamTypeChoice;
}

OfxStatus paramDefine(
    OfxParamSetHandle set, const char* type, const char* name, OfxPropertySetHandle* props)
{
    if (!set || !type || !name)
        return kOfxStatErrBadHandle;
    if (set->find(name))
        return kOfxStatErrExists;
    const std::string t = type;
    if (!isIntType(t) && t != kOfxParamTypeDouble && t != kOfxParamTypeGroup
        && t != kOfxParamTypeString)
        return kOfxStatErrUnknown;
    auto p = std::make_unique<OfxParamStruct>();
    p->type = t;
    p->name = name;
    p->props.setStrings(kOfxParamPropType, { t });
    p->props.setStrings(kOfxPropName, { name });
    if (props)
        *props = &p->props;
    set->params.push_back(std::move(p));
    return kOfxStatOK;
}

OfxStatus paramGetHandle(
    OfxParamSetHandle set, const char* name, OfxParamHandle* param, OfxPropertySetHandle* props)
{
    if (!set || !name || !param)
        return kOfxStatErrBadHandle;
    OfxParamStruct* p = set->find(name);
    if (!p)
        return kOfxStatErrUnknown;
    *param = p;
    if (props)
        *props = &p->props;
    return kOfxStatOK;
}

OfxStatus paramSetGetPropertySet(OfxParamSetHandle set, OfxPropertySetHandle* props)
{
    if (!set || !props)
        return kOfxStatErrBadHandle;
    *props = &set->props;
    return kOfxStatOK;
}

OfxStatus paramGetPropertySet(OfxParamHandle p, OfxPropertySetHandle* props)
{
    if (!p || !props)
        return kOfxStatErrBadHandle;
    *props = &p->props;
    return kOfxStatOK;
}

OfxStatus getValue(OfxParamHandle p, va_list ap)
{
    if (!p)
        return kOfxStatErrBadHandle;
    if (isIntType(p->type))
        *va_arg(ap, int*) = p->intValue;
    else if (p->type == kOfxParamTypeDouble)
        *va_arg(ap, double*) = p->doubleValue;
    else if (p->type == kOfxParamTypeString)
        *va_arg(ap, const char**) = p->stringValue.c_str(); // valid until the value changes
    else
        return kOfxStatErrUnsupported;
    return kOfxStatOK;
}

OfxStatus setValue(OfxParamHandle p, va_list ap)
{
    if (!p)
        return kOfxStatErrBadHandle;
    if (isIntType(p->type))
        p->intValue = va_arg(ap, int);
    else if (p->type == kOfxParamTypeDouble)
        p->doubleValue = va_arg(ap, double);
    else if (p->type == kOfxParamTypeString) {
        const char* v = va_arg(ap, const char*);
        p->stringValue = v ? v : "";
    } else
        return kOfxStatErrUnsupported;
    return kOfxStatOK;
}

OfxStatus paramGetValue(OfxParamHandle p, ...)
{
    va_list ap;
    va_start(ap, p);
    const OfxStatus s = getValue(p, ap);
    va_end(ap);
    return s;
}

OfxStatus paramGetValueAtTime(OfxParamHandle p, OfxTime time, ...)
{
    va_list ap;
    va_start(ap, time);
    const OfxStatus s = getValue(p, ap); // no animation in this host
    va_end(ap);
    return s;
}

OfxStatus paramGetDerivative(OfxParamHandle, OfxTime, ...)
{
    return kOfxStatErrUnsupported;
}
OfxStatus paramGetIntegral(OfxParamHandle, OfxTime, OfxTime, ...)
{
    return kOfxStatErrUnsupported;
}

OfxStatus paramSetValue(OfxParamHandle p, ...)
{
    va_list ap;
    va_start(ap, p);
    const OfxStatus s = setValue(p, ap);
    va_end(ap);
    return s;
}

OfxStatus paramSetValueAtTime(OfxParamHandle p, OfxTime time, ...)
{
    va_list ap;
    va_start(ap, time);
    const OfxStatus s = setValue(p, ap);
    va_end(ap);
    return s;
}

OfxStatus paramGetNumKeys(OfxParamHandle p, unsigned int* n)
{
    if (!p || !n)
        return kOfxStatErrBadHandle;
    *n = 0;
    return kOfxStatOK;
}
OfxStatus paramGetKeyTime(OfxParamHandle, unsigned int, OfxTime*)
{
    return kOfxStatErrBadIndex;
}
OfxStatus paramGetKeyIndex(OfxParamHandle, OfxTime, int, int*)
{
    return kOfxStatFailed;
}
OfxStatus paramDeleteKey(OfxParamHandle, OfxTime)
{
    return kOfxStatErrBadIndex;
}
OfxStatus paramDeleteAllKeys(OfxParamHandle)
{
    return kOfxStatOK;
}
OfxStatus paramCopy(OfxParamHandle, OfxParamHandle, OfxTime, const OfxRangeD*)
{
    return kOfxStatErrUnsupported;
}
OfxStatus paramEditBegin(OfxParamSetHandle, const char*)
{
    return kOfxStatOK;
}
OfxStatus paramEditEnd(OfxParamSetHandle)
{
    return kOfxStatOK;
}

const OfxParameterSuiteV1 kParameterSuite = {
    paramDefine,
    paramGetHandle,
    paramSetGetPropertySet,
    paramGetPropertySet,
    paramGetValue,
    paramGetValueAtTime,
    paramGetDerivative,
    paramGetIntegral,
    paramSetValue,
    paramSetValueAtTime,
    paramGetNumKeys,
    paramGetKeyTime,
    paramGetKeyIndex,
    paramDeleteKey,
    paramDeleteAllKeys,
    paramCopy,
    paramEditBegin,
    paramEditEnd,
};

// ---- memory -------------------------------------------------------------------------------------

OfxStatus memoryAlloc(void*, size_t n, void** data)
{
    if (!data)
        return kOfxStatErrBadHandle;
    *data = std::malloc(n);
    return *data ? kOfxStatOK : kOfxStatErrMemory;
}
OfxStatus memoryFree(void* data)
{
    std::free(data);
    return kOfxStatOK;
}
const OfxMemorySuiteV1 kMemorySuite = { memoryAlloc, memoryFree };

// ---- threads ------------------------------------------------------------------------------------

thread_local unsigned int t_threadIndex = 0;
thread_local bool t_spawned = false;

OfxStatus multiThread(OfxThreadFunctionV1 func, unsigned int n, void* arg)
{
    if (!func)
        return kOfxStatErrBadHandle;
    if (n <= 1) {
        func(0, 1, arg);
        return kOfxStatOK;
    }
    std::vector<std::thread> threads;
    for (unsigned int i = 0; i < n; ++i)
        threads.emplace_back([=] {
            t_threadIndex = i;
            t_spawned = true;
            func(i, n, arg);
        });
    for (std::thread& t : threads)
        t.join();
    return kOfxStatOK;
}
OfxStatus numCPUs(unsigned int* n)
{
    if (!n)
        return kOfxStatErrBadHandle;
    *n = std::max(2u, std::thread::hardware_concurrency()); // at least 2: exercise the split
    return kOfxStatOK;
}
OfxStatus threadIndex(unsigned int* i)
{
    if (!i)
        return kOfxStatErrBadHandle;
    *i = t_threadIndex;
    return kOfxStatOK;
}
int isSpawned()
{
    return t_spawned;
}
OfxStatus mutexCreate(OfxMutexHandle* m, int)
{
    if (!m)
        return kOfxStatErrBadHandle;
    *m = reinterpret_cast<OfxMutexHandle>(new std::recursive_mutex);
    return kOfxStatOK;
}
std::recursive_mutex* asMutex(OfxMutexHandle m)
{
    return reinterpret_cast<std::recursive_mutex*>(m);
}
OfxStatus mutexDestroy(const OfxMutexHandle m)
{
    delete asMutex(m);
    return kOfxStatOK;
}
OfxStatus mutexLock(const OfxMutexHandle m)
{
    asMutex(m)->lock();
    return kOfxStatOK;
}
OfxStatus mutexUnLock(const OfxMutexHandle m)
{
    asMutex(m)->unlock();
    return kOfxStatOK;
}
OfxStatus mutexTryLock(const OfxMutexHandle m)
{
    return asMutex(m)->try_lock() ? kOfxStatOK : kOfxStatFailed;
}
const OfxMultiThreadSuiteV1 kThreadSuite = { multiThread, numCPUs, threadIndex, isSpawned,
    mutexCreate, mutexDestroy, mutexLock, mutexUnLock, mutexTryLock };

// ---- messages -----------------------------------------------------------------------------------

OfxStatus message(void* handle, const char* type, const char*, const char* format, ...)
{
    char text[1024];
    va_list ap;
    va_start(ap, format);
    std::vsnprintf(text, sizeof text, format ? format : "", ap);
    va_end(ap);
    auto* effect = static_cast<OfxImageEffectHandle>(handle);
    if (effect && effect->host)
        effect->host->addMessage(std::string(type ? type : "") + ": " + text);
    return kOfxStatOK;
}
const OfxMessageSuiteV1 kMessageSuite = { message };

} // namespace

const void* fetchSuite(OfxPropertySetHandle, const char* name, int version)
{
    if (!name || version != 1)
        return nullptr;
    const std::string n = name;
    if (n == kOfxPropertySuite)
        return propertySuite();
    if (n == kOfxImageEffectSuite)
        return imageEffectSuite();
    if (n == kOfxParameterSuite)
        return &kParameterSuite;
    if (n == kOfxMemorySuite)
        return &kMemorySuite;
    if (n == kOfxMultiThreadSuite)
        return &kThreadSuite;
    if (n == kOfxMessageSuite)
        return &kMessageSuite;
    return nullptr;
}

} // namespace ofxhost
