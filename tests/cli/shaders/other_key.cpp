// A shared library that claims to be a shader module built against another Facet
// (tests/cli/user_shader_cli_test.cpp): facet reads its key, sees it is not its own and refuses it
// before it calls anything else (facet_shader_module, which would be a null module, is never called).
extern "C" __attribute__((visibility("default"))) const char* facet_shader_abi() {
    return "facet 0.0.0, headers 0123456789abcdef, GNU 1.0 (a test's stand-in)";
}
extern "C" __attribute__((visibility("default"))) const void* facet_shader_module() {
    return nullptr;
}
