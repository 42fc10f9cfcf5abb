#include "app/commands.h"

int main(int argc, char** argv) { return glint::runCli(argc, argv); }
