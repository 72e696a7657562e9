#pragma once
// Generated sequences kept across runs: a sweep's points and every run's start-up read a
// configuration's sequence from a file instead of scheduling it again (about 40 ms each, and
// a report names two per FHG). Plain C++.
//
// The folder is $SURFVP_CACHE, else $XDG_CACHE_HOME/surfvp, else ~/.cache/surfvp;
// SURFVP_CACHE=off keeps nothing on disk. Each file holds one configuration's sequence and
// the key it was made for: every SequenceParams field and a fingerprint of the generator's
// source (taken by the build), so a changed generator never reads an old sequence. Files are
// written whole under a temporary name and renamed into place, so concurrent runs share the
// folder safely; a file that is not a sound cache entry (models/host/disk_cache.h: its
// size and checksum, a regular file) or does not read back as its key is made again. A
// folder that cannot be written costs only the time: the sequence is generated as before.
#include <filesystem>
#include <optional>
#include <string>

#include "sequence_generator.h"

namespace surfvp::fhg {

// generate_sequence, remembered per configuration for the life of the process (a platform
// with several FHGs, and re-simulations forked from one process, make each sequence once)
// and across runs in the cache folder.
const Sequence& cached_sequence(const SequenceParams& params);

// The cache folder, or nothing when SURFVP_CACHE=off.
std::optional<std::filesystem::path> sequence_cache_folder();

// Everything a sequence depends on, as one line of text.
std::string sequence_key(const SequenceParams& params);

// The sequence from `folder` if a file there holds it for `params`; otherwise generated and
// stored there (when the folder can be written).
Sequence stored_sequence(const SequenceParams& params, const std::filesystem::path& folder);

// A sequence as text and back; read_sequence_text returns nothing for text that is not one.
std::string sequence_text(const std::string& key, const Sequence& sequence);
std::optional<Sequence> read_sequence_text(const std::string& text, const std::string& key);

}  // namespace surfvp::fhg
