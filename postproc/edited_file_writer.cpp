#include "postproc/edited_file_writer.hpp"

#include <stdexcept>
#include <utility>

namespace roprec::postproc {

EditedFileWriter::EditedFileWriter(Program& p, int file, ByteWriter write)
    : p_(p), file_(file), write_(std::move(write)) {
  buf_.reserve(kBufferBytes + 4096);
}

void EditedFileWriter::emit(std::string_view bytes) {
  if (buf_.size() + bytes.size() > kBufferBytes && !buf_.empty()) {
    write_(buf_);
    buf_.clear();
  }
  if (bytes.size() >= kBufferBytes) {
    write_(bytes);
  } else {
    buf_.append(bytes);
  }
}

void EditedFileWriter::flushBefore(std::size_t offset) {
  const std::string& b = p_.files[static_cast<std::size_t>(file_)].bytes;
  offset = std::min(offset, b.size());
  if (offset < pos_) return;
  const auto first = p_.edits.lower_bound({file_, 0U});
  auto it = first;
  std::size_t end = offset;  // the bytes written up to here
  for (; it != p_.edits.end() && it->first.first == file_ && it->second.offset < offset; ++it) {
    const Edit& e = it->second;
    if (e.offset < pos_ || e.offset + e.length > b.size())
      throw std::logic_error("overlapping edits in " +
                             p_.files[static_cast<std::size_t>(file_)].path);
    if (e.offset + e.length > offset) {  // reaches past `offset`: written by a later flush
      end = e.offset;
      break;
    }
    emit(std::string_view(b).substr(pos_, e.offset - pos_));
    emit(e.text);
    pos_ = e.offset + e.length;
  }
  if (end > pos_) {
    emit(std::string_view(b).substr(pos_, end - pos_));
    pos_ = end;
  }
  p_.edits.erase(first, it);
  if (!buf_.empty()) {
    write_(buf_);
    buf_.clear();
  }
}

void EditedFileWriter::finish() {
  flushBefore(p_.files[static_cast<std::size_t>(file_)].bytes.size());
  // an insertion at the very end of the file (offset == size) is not before it
  const std::string& b = p_.files[static_cast<std::size_t>(file_)].bytes;
  const auto first = p_.edits.lower_bound({file_, 0U});
  auto it = first;
  for (; it != p_.edits.end() && it->first.first == file_; ++it) {
    const Edit& e = it->second;
    if (e.offset < pos_ || e.offset + e.length > b.size())
      throw std::logic_error("overlapping edits in " +
                             p_.files[static_cast<std::size_t>(file_)].path);
    emit(std::string_view(b).substr(pos_, e.offset - pos_));
    emit(e.text);
    pos_ = e.offset + e.length;
  }
  p_.edits.erase(first, it);
  emit(std::string_view(b).substr(pos_));
  pos_ = b.size();
  if (!buf_.empty()) write_(buf_);
  buf_.clear();
}

}  // namespace roprec::postproc
