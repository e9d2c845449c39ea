// A shared library that is no shader module (tests/cli/user_shader_cli_test.cpp): it exports a plain C
// function, and neither facet_shader_abi nor facet_shader_module.
extern "C" __attribute__((visibility("default"))) int facet_test_plain_function() {
    return 42;
}
