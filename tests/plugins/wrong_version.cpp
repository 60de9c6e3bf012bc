// A plugin built for another plugin API version, which bvhlab must refuse naming both versions.
#include "framework/plugin/plugin_api.h"

BVHLAB_PLUGIN_EXPORT int bvhlab_plugin_api_version() { return BVHLAB_PLUGIN_API_VERSION + 998; }
BVHLAB_PLUGIN_EXPORT void bvhlab_register_plugin(bvhlab::PluginRegistrar&) {}
