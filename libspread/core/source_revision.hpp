#pragma once
// The git revision the binaries were built from (`git describe --always --dirty`), or "unknown" outside
// a git checkout. Recorded with every table run beside the version number, so a table says exactly which
// code computed it.
namespace spread {

const char* source_revision();

}  // namespace spread
