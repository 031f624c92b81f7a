// A sentence the application builds for a person (a setting-day candidate's
// reasons, a report's verdict, a setting day's notes), kept as its message
// id and arguments (issue 32) so the web translates it by id: the English
// text is the id with its "{1}".."{9}" filled in, which the JSON API and the
// CLI keep showing. The ids are English sentences passed to Msg/MsgN as
// string literals: tests/i18n_check.py extracts them from src/app with
// xgettext (keywords Msg:1, MsgN:1,2) into the catalogs, and fails the build
// when po/de.po or po/fr.po lacks one, so a new or changed sentence cannot
// stay English unnoticed. web::TrMessage (web/error_text.h) writes one in a
// page's language.
//
//   Message m = MsgN("{1} of {2} move new against its inputs",
//                    "{1} of {2} moves new against its inputs", 8, {"5", "8"});
//   m.English()        -> "5 of 8 moves new against its inputs"
//   web::TrMessage("de", m) -> "5 von 8 Zügen neu gegenüber den Eingaben"
//
// An argument is itself a Message: a name or number shown as it is (built
// implicitly from a std::string), a word the catalogs have (Word: a style's
// name, translated) or a nested message (translated with its own arguments).
// Value type.
#ifndef SB_APP_MESSAGE_H_
#define SB_APP_MESSAGE_H_

#include <string>
#include <vector>

namespace sb::app {

struct Message {
  enum class Kind { kText, kWord, kMessage, kList };
  Kind kind = Kind::kText;
  // kMessage: the English id (singular when `plural` is set); kList: the
  // separator of its args; else the text.
  std::string id;
  std::string plural;  // kMessage: the plural id ("" = none)
  long long n = 0;     // which of id/plural (English: 1 = id); the language's rule elsewhere
  std::vector<Message> args;  // "{1}".."{9}"

  Message() = default;
  Message(std::string text) : id(std::move(text)) {}  // NOLINT: a name or number, shown as is
  Message(const char* text) : id(text) {}             // NOLINT: same

  // The sentence in English (its id, or plural form, with the arguments).
  std::string English() const;
  bool empty() const { return kind != Kind::kMessage && id.empty(); }
  bool operator==(const Message&) const = default;
};

// A message id kept as a value (a verdict such as "soft" that the JSON API
// returns in English and the pages translate): `id` itself, marked for the
// catalogs' extraction.
constexpr const char* MsgId(const char* id) { return id; }
// A catalog message (`id` a string literal: extracted for the catalogs).
Message Msg(const char* id, std::vector<Message> args = {});
// A catalog message with a singular and a plural form, chosen by `n`.
Message MsgN(const char* singular, const char* plural, long long n, std::vector<Message> args = {});
// A single word of the catalogs (a style's name such as "heel hook", marked
// for extraction where its table is): translated, not filled in.
Message Word(std::string word);
// A number printed with a decimal point ("0.31"), shown with the decimal
// mark of a page's language ("0,31" in German and French: the catalog
// message "{1}.{2}"); its English() is `number` itself. Without a point:
// `number` as it is.
Message Decimal(const std::string& number);
// `items` one after the other, `separator` ("; ", ", ") between them.
Message List(std::vector<Message> items, std::string separator);

}  // namespace sb::app

#endif  // SB_APP_MESSAGE_H_
