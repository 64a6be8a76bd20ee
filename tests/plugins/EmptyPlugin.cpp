// A test plugin that registers nothing: loading it must warn, not fail.
extern "C" int magEmptyPluginMarker() { return 42; }
