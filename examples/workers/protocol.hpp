// protocol.hpp - the request reader and answer writer of offbench's
// external-method protocol (docs/external-methods.md, protocol 1), shared
// by the C++ workers in examples/ (occt/occt_worker.cpp,
// lib2geom/lib2geom_worker.cpp): standard C++ only, header only.
#ifndef OB_WORKER_PROTOCOL_HPP
#define OB_WORKER_PROTOCOL_HPP

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace ob_worker {

// ------------------------------------------------------------ the request

// A JSON value of the kinds a request holds: number, array, object.
// Strings, true, false and null never occur in a request, so they are
// refused as errors rather than parsed.
struct Value {
    enum Kind { NUM, ARR, OBJ } kind = NUM;
    double num = 0;
    std::vector<Value> arr;
    std::map<std::string, Value> obj;
};

struct BadRequest {
    std::string why;
};

// A strict recursive-descent reader of one line (RFC 8259 numbers, keys
// without escapes: a request's keys are plain names).
class Reader {
  public:
    explicit Reader(const std::string &s) : s_(s) {}
    Value whole()
    {
        Value v = value(0);
        space();
        if (i_ != s_.size())
            fail("text after the value");
        return v;
    }

  private:
    const std::string &s_;
    size_t i_ = 0;

    [[noreturn]] void fail(const std::string &why) const
    {
        throw BadRequest{why + " at byte " + std::to_string(i_)};
    }
    void space()
    {
        while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\r' || s_[i_] == '\n'))
            i_++;
    }
    bool eat(char c)
    {
        space();
        if (i_ < s_.size() && s_[i_] == c)
            return ++i_, true;
        return false;
    }
    Value value(int depth)
    {
        if (depth > 4)   // a request nests 3 deep: points -> point -> number
            fail("nested too deep");
        space();
        if (eat('['))
            return array(depth);
        if (eat('{'))
            return object(depth);
        return number();
    }
    Value array(int depth)
    {
        Value v;
        v.kind = Value::ARR;
        if (eat(']'))
            return v;
        do
            v.arr.push_back(value(depth + 1));
        while (eat(','));
        if (!eat(']'))
            fail("expected ',' or ']'");
        return v;
    }
    std::string key()
    {
        if (!eat('"'))
            fail("expected a key");
        const size_t at = i_;
        while (i_ < s_.size() && (std::isalnum((unsigned char)s_[i_]) || s_[i_] == '_'))
            i_++;
        if (i_ >= s_.size() || s_[i_] != '"')
            fail("a key holds letters, digits and '_' only");
        return s_.substr(at, i_++ - at);
    }
    Value object(int depth)
    {
        Value v;
        v.kind = Value::OBJ;
        if (eat('}'))
            return v;
        do {
            const std::string k = key();
            if (!eat(':'))
                fail("expected ':'");
            if (!v.obj.emplace(k, value(depth + 1)).second)
                fail("key \"" + k + "\" twice");
        } while (eat(','));
        if (!eat('}'))
            fail("expected ',' or '}'");
        return v;
    }
    // JSON's number grammar exactly (no NaN, no hex, no leading '+'), read by strtod.
    Value number()
    {
        const size_t at = i_;
        auto digits = [&] {
            const size_t d = i_;
            while (i_ < s_.size() && std::isdigit((unsigned char)s_[i_]))
                i_++;
            return i_ > d;
        };
        if (i_ < s_.size() && s_[i_] == '-')
            i_++;
        if (i_ < s_.size() && s_[i_] == '0')
            i_++;
        else if (!digits())
            fail("not a number");
        if (i_ < s_.size() && s_[i_] == '.' && (++i_, !digits()))
            fail("no digits after '.'");
        if (i_ < s_.size() && (s_[i_] == 'e' || s_[i_] == 'E')) {
            i_++;
            if (i_ < s_.size() && (s_[i_] == '+' || s_[i_] == '-'))
                i_++;
            if (!digits())
                fail("no digits in the exponent");
        }
        Value v;
        v.num = std::strtod(s_.substr(at, i_ - at).c_str(), nullptr);
        if (!std::isfinite(v.num))
            fail("a number out of range");
        return v;
    }
};

struct Request {
    long id = -1;          // -1 until read: an error answer then says "id": null
    int degree = 0;
    std::vector<double> x, y, w;
    double d = 0, tol = 0;
    Value params;          // an object; the worker checks it against its hello
};

inline const Value &field(const Value &o, const char *k)
{
    auto it = o.obj.find(k);
    if (it == o.obj.end())
        throw BadRequest{std::string("no \"") + k + "\""};
    return it->second;
}

inline double number_of(const Value &v, const char *what)
{
    if (v.kind != Value::NUM)
        throw BadRequest{std::string("\"") + what + "\" is not a number"};
    return v.num;
}

// The request's shape, exactly (docs/external-methods.md "Request"), into
// r: its id first, so that an error about the rest can name it; a degree
// from 1 to max_degree (what the worker's library takes).
inline void request_of(const Value &v, Request &r, int max_degree)
{
    if (v.kind != Value::OBJ)
        throw BadRequest{"not a JSON object"};
    const double id = number_of(field(v, "id"), "id");
    if (id != std::floor(id) || id < 0 || id > 1e15)
        throw BadRequest{"\"id\" is not a whole number >= 0"};
    r.id = (long)id;
    for (const auto &kv : v.obj)
        if (kv.first != "id" && kv.first != "degree" && kv.first != "points" && kv.first != "weights" &&
            kv.first != "d" && kv.first != "tol" && kv.first != "params")
            throw BadRequest{"unknown key \"" + kv.first + "\""};
    const double deg = number_of(field(v, "degree"), "degree");
    if (deg != std::floor(deg) || deg < 1 || deg > max_degree)
        throw BadRequest{"\"degree\" is not a whole number from 1 to " + std::to_string(max_degree)};
    r.degree = (int)deg;
    const Value &p = field(v, "points"), &w = field(v, "weights");
    if (p.kind != Value::ARR || (int)p.arr.size() != r.degree + 1)
        throw BadRequest{"\"points\" is not degree + 1 points"};
    if (w.kind != Value::ARR || w.arr.size() != p.arr.size())
        throw BadRequest{"\"weights\" is not degree + 1 numbers"};
    for (size_t i = 0; i < p.arr.size(); i++) {
        if (p.arr[i].kind != Value::ARR || p.arr[i].arr.size() != 2)
            throw BadRequest{"\"points\"[" + std::to_string(i) + "] is not [x, y]"};
        r.x.push_back(number_of(p.arr[i].arr[0], "points"));
        r.y.push_back(number_of(p.arr[i].arr[1], "points"));
        r.w.push_back(number_of(w.arr[i], "weights"));
        if (!(r.w.back() > 0))
            throw BadRequest{"a weight is not > 0"};
    }
    r.d = number_of(field(v, "d"), "d");
    r.tol = number_of(field(v, "tol"), "tol");
    if (!(r.tol > 0))
        throw BadRequest{"\"tol\" is not > 0"};
    r.params = field(v, "params");
    if (r.params.kind != Value::OBJ)
        throw BadRequest{"\"params\" is not an object"};
}

// Quotes an error message as a JSON string (OCCT's messages are ASCII;
// anything else becomes '?').
inline std::string quoted(const std::string &m)
{
    std::string s = "\"";
    for (unsigned char c : m)
        s += c == '"' || c == '\\' ? std::string("\\") + (char)c : c < 0x20 || c >= 0x7f ? "?" : std::string(1, (char)c);
    return s + "\"";
}

inline std::string error_json(long id, const std::string &why, const char *status = "fail")
{
    return std::string("{\"id\":") + (id < 0 ? "null" : std::to_string(id)) + ",\"error\":" + quoted(why) +
           ",\"status\":\"" + status + "\"}";
}

}  // namespace ob_worker

#endif
