// SPDX-License-Identifier: Apache-2.0
// The binary's two exported entry points and the action boundary: no exception leaves it.
#include "DenoiseEffect.h"
#include "ofx_support.h"

#include <new>

namespace {

void setHost(OfxHost* host)
{
    afnofx::suites().host = host;
}

OfxStatus mainEntry(const char* action, const void* handle, OfxPropertySetHandle inArgs,
    OfxPropertySetHandle outArgs)
{
    auto* effect = static_cast<OfxImageEffectHandle>(const_cast<void*>(handle));
    try {
        return afnofx::denoiseAction(action ? action : "", effect, inArgs, outArgs);
    } catch (const afnofx::OfxError& e) {
        afnofx::postError(effect, std::string("afn Denoise: ") + e.what());
        return e.status();
    } catch (const std::bad_alloc&) {
        return kOfxStatErrMemory;
    } catch (const std::exception& e) {
        afnofx::postError(effect, std::string("afn Denoise: ") + e.what());
        return kOfxStatFailed;
    } catch (...) {
        return kOfxStatErrUnknown;
    }
}

OfxPlugin g_denoise
    = { kOfxImageEffectPluginApi, kOfxImageEffectPluginApiVersion, afnofx::kDenoiseIdentifier,
          afnofx::kDenoiseVersionMajor, afnofx::kDenoiseVersionMinor, setHost, mainEntry };

} // namespace

extern "C" {

/// Number of plugins in this binary (one: org.afn.Denoise).
__attribute__((visibility("default"))) int OfxGetNumberOfPlugins(void)
{
    return 1;
}

/// The nth plugin, NULL when out of range.
__attribute__((visibility("default"))) OfxPlugin* OfxGetPlugin(int nth)
{
    return nth == 0 ? &g_denoise : nullptr;
}

} // extern "C"
