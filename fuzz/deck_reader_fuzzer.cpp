// libFuzzer target for the deck reader: any byte string given to
// iga::io::read_deck_text must either parse or throw iga::DeckError (bad input,
// the expected outcome). Any other exception, a crash, or an ASan/UBSan report is
// a finding. Built only by scripts/fuzz_deck_reader.sh (clang, -fsanitize=fuzzer).
#include "core/error.hpp"
#include "io/deck_reader.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        (void)iga::io::read_deck_text(text, "fuzz.yaml", "/tmp", {});
    } catch (const iga::DeckError&) {
        // expected: a malformed deck is reported, not crashed on
    }
    // anything else propagates: libFuzzer reports an uncaught exception as a crash
    return 0;
}
