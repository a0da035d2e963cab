// The multipart/related state machine: preamble, delimiters, transport padding, part headers, data, epilogue.
#include "vots/pacs/MultipartSplitter.h"

#include "vots/fit/Error.h"

#include <algorithm>
#include <cctype>

namespace vots::pacs {
namespace {

constexpr std::size_t MAX_BOUNDARY_LENGTH = 70; // RFC 2046
constexpr std::size_t MAX_PADDING_BYTES = 1024;

[[noreturn]] void malformed(const std::string& problem) {
    throw fit::InputError("malformed multipart body: " + problem);
}

std::string lowerCase(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text;
}

std::string trimmed(const std::string& text) {
    const std::size_t first = text.find_first_not_of(" \t");
    if (first == std::string::npos) return {};
    return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

} // namespace

std::string multipartBoundary(const std::string& contentType) {
    const std::string lower = lowerCase(contentType);
    if (trimmed(lower.substr(0, lower.find(';'))).rfind("multipart/", 0) != 0)
        throw fit::InputError("the answer is '" + contentType.substr(0, 200) + "', not a multipart body");
    std::size_t at = lower.find(';');
    while (at != std::string::npos) {
        const std::size_t next = lower.find(';', at + 1);
        const std::string parameter =
            trimmed(contentType.substr(at + 1, next == std::string::npos ? next : next - at - 1));
        const std::size_t equals = parameter.find('=');
        if (equals != std::string::npos && lowerCase(trimmed(parameter.substr(0, equals))) == "boundary") {
            std::string value = trimmed(parameter.substr(equals + 1));
            if (value.size() >= 2 && value.front() == '"' && value.back() == '"')
                value = value.substr(1, value.size() - 2);
            if (value.empty() || value.size() > MAX_BOUNDARY_LENGTH)
                throw fit::InputError("the multipart boundary must be 1.." +
                                      std::to_string(MAX_BOUNDARY_LENGTH) + " characters");
            return value;
        }
        at = next;
    }
    throw fit::InputError("the multipart answer names no boundary");
}

MultipartSplitter::MultipartSplitter(const std::string& boundary, MultipartHandlers handlers)
    : mDelimiter("\r\n--" + boundary), mHandlers(std::move(handlers)) {
    if (boundary.empty() || boundary.size() > MAX_BOUNDARY_LENGTH)
        throw fit::InputError("the multipart boundary must be 1.." + std::to_string(MAX_BOUNDARY_LENGTH) +
                              " characters");
    // The first delimiter may open the body without the CRLF that belongs to every later one.
    mPending = "\r\n";
}

void MultipartSplitter::feed(const char* data, std::size_t size) {
    if (mState == State::Epilogue) return; // the epilogue is ignored
    mPending.append(data, size);
    step();
}

void MultipartSplitter::finish() {
    if (mState != State::Epilogue)
        throw fit::InputError(
            "the multipart body ended before its closing boundary (the stream was cut) after " +
            std::to_string(mPartsCompleted) + " complete parts");
}

void MultipartSplitter::step() {
    bool progressed = true;
    while (progressed && mState != State::Epilogue) {
        switch (mState) {
        case State::Preamble:
            progressed = skipToFirstDelimiter();
            break;
        case State::AfterDelimiter:
            progressed = readAfterDelimiter();
            break;
        case State::Padding:
            progressed = readPadding();
            break;
        case State::Headers:
            progressed = readHeaders();
            break;
        case State::Data:
            progressed = readData();
            break;
        case State::Epilogue:
            break;
        }
    }
    if (mState == State::Epilogue) mPending.clear();
}

bool MultipartSplitter::skipToFirstDelimiter() {
    const std::size_t at = mPending.find(mDelimiter);
    if (at == std::string::npos) {
        // Keep what could be the start of a delimiter; the preamble itself is dropped.
        const std::size_t keep = std::min(mPending.size(), mDelimiter.size() - 1);
        mPending.erase(0, mPending.size() - keep);
        return false;
    }
    mPending.erase(0, at + mDelimiter.size());
    mState = State::AfterDelimiter;
    return true;
}

bool MultipartSplitter::readAfterDelimiter() {
    if (mPending.size() < 2) return false;
    if (mPending.compare(0, 2, "--") == 0) {
        mState = State::Epilogue;
        return true;
    }
    mPaddingBytes = 0;
    mState = State::Padding;
    return true;
}

bool MultipartSplitter::readPadding() {
    std::size_t at = 0;
    while (at < mPending.size() && (mPending[at] == ' ' || mPending[at] == '\t'))
        ++at;
    mPaddingBytes += at;
    mPending.erase(0, at);
    if (mPaddingBytes > MAX_PADDING_BYTES)
        malformed("more than " + std::to_string(MAX_PADDING_BYTES) + " bytes of padding after a boundary");
    if (mPending.size() < 2) return false;
    if (mPending.compare(0, 2, "\r\n") != 0)
        malformed("a boundary line is followed by other text than a line end");
    mPending.erase(0, 2);
    mState = State::Headers;
    return true;
}

bool MultipartSplitter::readHeaders() {
    std::string block;
    if (mPending.compare(0, 2, "\r\n") == 0) {
        mPending.erase(0, 2); // a part without header fields
    } else {
        const std::size_t end = mPending.find("\r\n\r\n");
        if (end == std::string::npos || end > MAX_HEADER_BYTES) {
            if (std::min(end, mPending.size()) > MAX_HEADER_BYTES)
                malformed("a part's headers are longer than " + std::to_string(MAX_HEADER_BYTES) + " bytes");
            return false;
        }
        block = mPending.substr(0, end + 2);
        mPending.erase(0, end + 4);
    }
    parseHeaders(block);
    mState = State::Data;
    return true;
}

void MultipartSplitter::parseHeaders(const std::string& block) {
    PartHeaders headers;
    std::string lastName;
    std::size_t at = 0;
    while (at < block.size()) {
        const std::size_t end = block.find("\r\n", at);
        const std::string line = block.substr(at, end - at);
        at = end + 2;
        if (!line.empty() && (line.front() == ' ' || line.front() == '\t')) {
            if (lastName.empty()) malformed("a part's header block starts with a continuation line");
            headers[lastName] += " " + trimmed(line);
            continue;
        }
        const std::size_t colon = line.find(':');
        if (colon == std::string::npos || colon == 0) malformed("a part's header line has no 'name:'");
        lastName = lowerCase(trimmed(line.substr(0, colon)));
        headers[lastName] = trimmed(line.substr(colon + 1));
    }
    if (mHandlers.partBegin) mHandlers.partBegin(headers);
}

bool MultipartSplitter::readData() {
    const std::size_t at = mPending.find(mDelimiter);
    if (at == std::string::npos) {
        // Everything but a possible delimiter's beginning is the part's.
        const std::size_t keep = std::min(mPending.size(), mDelimiter.size() - 1);
        const std::size_t emit = mPending.size() - keep;
        if (emit > 0) {
            if (mHandlers.partData) mHandlers.partData(mPending.data(), emit);
            mPending.erase(0, emit);
        }
        return false;
    }
    if (at > 0 && mHandlers.partData) mHandlers.partData(mPending.data(), at);
    mPending.erase(0, at + mDelimiter.size());
    if (mHandlers.partEnd) mHandlers.partEnd();
    ++mPartsCompleted;
    mState = State::AfterDelimiter;
    return true;
}

} // namespace vots::pacs
