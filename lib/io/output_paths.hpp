#pragma once
// The files a run writes, and the guard that keeps them off the files it reads.
//
// A run writes its results file (output.file, or -o) through a temporary file that
// finish() renames onto it, and with output.paraview the XDMF index beside it
// (xdmf_path). Before anything is built or written, check_output_paths refuses,
// as bad input (DeckError, exit 2), a results or XDMF path that is an input of the
// run (the deck itself, the G+Smo XML geometry files it reads), a folder, or an
// existing device, FIFO or socket (the rename would replace it by a file). Paths
// are compared as files, not as strings: std::filesystem::equivalent when both
// exist (symlinks, hard links, "./deck.yaml" vs "deck.yaml"), else the same
// normalized absolute path with the symlinks of its existing part resolved.

#include "io/deck.hpp"

#include <string>
#include <vector>

namespace iga::io {

/// The ParaView index written beside a results file: "<results without .h5>.xdmf".
std::string xdmf_path(const std::string& results_file);

/// True if the two paths name the same file (see the header paragraph).
bool same_file(const std::string& a, const std::string& b);

/// The files a deck makes a run read: the deck itself (Deck::source_file) and each
/// body's geometry.file, resolved against the deck's folder.
std::vector<std::string> input_files(const Deck& deck);

/// Where output.file came from, for the location of the message.
enum class OutputOrigin {
    deck,        ///< the deck's output.file, or its default (the deck's name with .h5)
    set_option,  ///< --set output.file=... (or --set output={file: ...})
    o_option     ///< -o / --output
};

/// The origin of output.file given the command line: -o wins over --set, --set over the deck.
OutputOrigin output_origin(bool o_option_given, const std::vector<std::string>& set_overrides);

/// The bad-input error of a results file (`reason`) where output.file came from:
/// located at output.file in the deck (`deck_file`), or at "<command line>" for --set
/// and -o; for -o the reason ends with " (the -o option)".
DeckError output_error(const std::string& deck_file, const std::string& results, OutputOrigin origin,
                       const std::string& reason);

/// Throws DeckError, located at output.file in the deck, at "<command line>" for --set,
/// or naming the -o option, if the results file or (with output.paraview) its XDMF
/// index is one of `inputs`, a folder or an existing non-regular file. Touches nothing.
void check_output_paths(const Deck& deck, const std::vector<std::string>& inputs, OutputOrigin origin);

}  // namespace iga::io
