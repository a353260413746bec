#include "config/YamlDocumentScan.hpp"

#include <yaml-cpp/eventhandler.h>

#include <sstream>

namespace fldsim {

namespace {

// Records document starts and each document's first node; ignores everything else.
class DocumentEvents : public YAML::EventHandler {
 public:
  explicit DocumentEvents(YamlDocumentScan& scan) : scan_(scan) {}

  void OnDocumentStart(const YAML::Mark& mark) override {
    if (scan_.documents > 0 && mark.pos == last_start_.pos) scan_.stalled_at = mark;
    last_start_ = mark;
    ++scan_.documents;
    awaiting_first_node_ = true;
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { node(mark); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { node(mark); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t, const std::string&) override {
    node(mark);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    node(mark);
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    node(mark);
  }
  void OnMapEnd() override {}

 private:
  void node(const YAML::Mark& mark) {
    if (awaiting_first_node_ && scan_.documents == 2) scan_.second_document = mark;
    awaiting_first_node_ = false;
  }

  YamlDocumentScan& scan_;
  YAML::Mark last_start_;
  bool awaiting_first_node_ = false;
};

}  // namespace

YamlDocumentScan scan_yaml_documents(const std::string& text) {
  YamlDocumentScan scan;
  std::istringstream stream(text);
  YAML::Parser parser(stream);
  DocumentEvents events(scan);
  while (!scan.stalled_at && scan.documents < kYamlDocumentsScanned && parser.HandleNextDocument(events)) {
  }
  return scan;
}

}  // namespace fldsim
