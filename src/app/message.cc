#include "app/message.h"

#include "base/fill_in.h"

namespace sb::app {

std::string Message::English() const {
  if (kind == Kind::kList) {
    std::string out;
    for (size_t i = 0; i < args.size(); ++i) out += (i ? id : "") + args[i].English();
    return out;
  }
  if (kind != Kind::kMessage) return id;
  std::vector<std::string> parts;
  parts.reserve(args.size());
  for (const Message& a : args) parts.push_back(a.English());
  return FillIn(n == 1 || plural.empty() ? id : plural, parts);
}

Message Msg(const char* id, std::vector<Message> args) {
  Message m;
  m.kind = Message::Kind::kMessage;
  m.id = id;
  m.args = std::move(args);
  return m;
}

Message MsgN(const char* singular, const char* plural, long long n, std::vector<Message> args) {
  Message m = Msg(singular, std::move(args));
  m.plural = plural;
  m.n = n;
  return m;
}

Message Word(std::string word) {
  Message m(std::move(word));
  m.kind = Message::Kind::kWord;
  return m;
}

Message Decimal(const std::string& number) {
  const size_t dot = number.find('.');
  if (dot == std::string::npos) return Message(number);
  // TRANSLATORS: a decimal number, {1} its whole part and {2} its fraction ("0.31"); German and
  // French write "{1},{2}".
  return Msg("{1}.{2}", {number.substr(0, dot), number.substr(dot + 1)});
}

Message List(std::vector<Message> items, std::string separator) {
  Message m(std::move(separator));
  m.kind = Message::Kind::kList;
  m.args = std::move(items);
  return m;
}

}  // namespace sb::app
