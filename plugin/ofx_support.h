// SPDX-License-Identifier: Apache-2.0
// Host suites fetched at load, typed property access that throws on failure, and the error type
// that carries an OFX status to the action boundary (Main.cpp turns it into a return code).
#pragma once

#include "ofx/ofx_api.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace afnofx {

/// Suites of the host. Property, image-effect and parameter suites are required; the others are
/// used when the host offers them.
struct Suites {
    OfxHost* host = nullptr;
    const OfxPropertySuiteV1* prop = nullptr;
    const OfxImageEffectSuiteV1* effect = nullptr;
    const OfxParameterSuiteV1* param = nullptr;
    const OfxMemorySuiteV1* memory = nullptr; ///< optional
    const OfxMultiThreadSuiteV1* thread = nullptr; ///< optional
    const OfxMessageSuiteV1* message = nullptr; ///< optional
};

/// The suites (valid between Load and Unload).
Suites& suites();
/// Fetch the suites from the host given to setHost; false when a required one is missing.
bool fetchSuites();

/// An error that becomes the given OFX status at the action boundary.
class OfxError : public std::runtime_error {
public:
    OfxError(OfxStatus status, const std::string& what)
        : std::runtime_error(what)
        , m_status(status)
    {
    }
    OfxStatus status() const { return m_status; }

private:
    OfxStatus m_status;
};

/// Throw OfxError(status, what + status) unless status is kOfxStatOK.
void check(OfxStatus status, const std::string& what);

/// Typed view of a property set; every accessor throws OfxError naming the property on failure.
class Props {
public:
    explicit Props(OfxPropertySetHandle handle)
        : m_handle(handle)
    {
    }
    OfxPropertySetHandle handle() const { return m_handle; }

    int getInt(const char* name, int index = 0) const;
    double getDouble(const char* name, int index = 0) const;
    std::string getString(const char* name, int index = 0) const;
    void* getPointer(const char* name, int index = 0) const;
    /// Value of an int property, or `fallback` when the host does not have it.
    int getIntOr(const char* name, int fallback) const;
    int dimension(const char* name) const;

    void set(const char* name, int value, int index = 0);
    void set(const char* name, double value, int index = 0);
    void set(const char* name, const char* value, int index = 0);
    void set(const char* name, const std::string& value, int index = 0);
    void setPointer(const char* name, void* value, int index = 0);
    void setDoubles(const char* name, const std::vector<double>& values);
    void setStrings(const char* name, const std::vector<std::string>& values);
    /// Set and ignore a host's refusal (for optional properties older hosts may not know).
    void trySet(const char* name, int value);

private:
    OfxPropertySetHandle m_handle;
};

/// Post an error message on an instance (or descriptor) when the host has a message suite.
void postError(void* handle, const std::string& message);
/// Write a note to the host's log (no dialog) when the host has a message suite.
void postNote(void* handle, const std::string& message);

} // namespace afnofx
