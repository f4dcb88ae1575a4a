// doctest entry point of the apps suite (glTF importer, image writer, ripple-render's command line).
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
