// Runs a libFuzzer target without libFuzzer (for compilers without it): every file in the
// corpus folder, then a fixed number of deterministic mutations of them (bytes flipped,
// inserted, deleted, truncated), so a plain build still exercises the target.
// Usage: TARGET CORPUS_DIR MUTATIONS
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size);

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: " << argv[0] << " CORPUS_DIR MUTATIONS\n";
    return 2;
  }
  std::vector<std::string> corpus;
  for (const auto& entry : std::filesystem::directory_iterator(argv[1])) {
    std::ifstream in(entry.path(), std::ios::binary);
    corpus.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  if (corpus.empty()) {
    std::cerr << "no seed inputs in " << argv[1] << "\n";
    return 1;
  }
  auto run = [](const std::string& input) {
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(input.data()), input.size());
  };
  for (const std::string& input : corpus) run(input);
  std::mt19937 random(1);
  const long mutations = std::atol(argv[2]);
  for (long i = 0; i < mutations; ++i) {
    std::string input = corpus[random() % corpus.size()];
    const int edits = 1 + static_cast<int>(random() % 4);
    for (int e = 0; e < edits && input.size() > 1; ++e) {
      const std::size_t at = 1 + random() % (input.size() - 1);  // byte 0 picks the reader
      constexpr char kInserted[] = "0123456789 -.e\n$<>\"=,*#";
      switch (random() % 4) {
        case 0:
          input[at] ^= static_cast<char>(1 << (random() % 8));
          break;
        case 1:
          input.insert(at, 1, kInserted[random() % (sizeof(kInserted) - 1)]);
          break;
        case 2:
          input.erase(at, 1 + random() % 8);
          break;
        case 3:
          input.resize(at);
          break;
      }
    }
    run(input);
  }
  std::cout << corpus.size() << " seeds and " << mutations << " mutations ran\n";
  return 0;
}
