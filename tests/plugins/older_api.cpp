// A plugin as an older bvhlab built them, whose entry points carried an API version number
// instead of an ABI: bvhlab must refuse it and ask for a rebuild (tests/apps/test_plugins.cpp).
// It includes no header of bvhlab's, as it was built against none of today's.
extern "C" __attribute__((visibility("default"))) int bvhlab_plugin_api_version() { return 5; }
extern "C" __attribute__((visibility("default"))) void bvhlab_register_plugin(void*) {}
