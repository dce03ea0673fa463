#pragma once
// Constants of the deterministic math (docs/numerics.md#detmath).
//
// Polynomial coefficients are relative-error minimax fits made with a Remez
// exchange in 60-digit arithmetic (mpmath), then rounded to the target type.
// The fitted interval and the fit's own error are given per table; the
// end-to-end error after rounding is what docs/numerics.md#detmath reports.
// Split constants (hi + lo) carry enough trailing zero bits in hi that k * hi
// is exact for every k the range reduction can produce.
#include <cstdint>

namespace cvt::dm::detail {

// --- exp: exp(r) ~ 1 + r + r^2 * P(r), |r| <= 0.3468 ---------------------
// double: 11 coeffs (r^2..r^12), fit error 2^-64.0
inline constexpr double kExpD[11] = {
    0x1.0000000000000p-1, 0x1.555555555555bp-3, 0x1.5555555555502p-5, 0x1.111111110ec34p-7,
    0x1.6c16c16c3065cp-10, 0x1.a01a01b38eacap-13, 0x1.a01a013635c57p-16, 0x1.71ddeff6d323fp-19,
    0x1.27e5b4aee2dc5p-22, 0x1.af6c3273e497dp-26, 0x1.1e3cfb4f8c83ep-29};
// float: 5 coeffs (r^2..r^6), fit error 2^-28.3
inline constexpr float kExpF[5] = {0x1.fffffcp-2f, 0x1.555490p-3f, 0x1.5558f4p-5f, 0x1.123a36p-7f,
                                   0x1.6a23a8p-10f};

// --- sin: sin(r) ~ r + r^3 * S(r^2), |r| <= 0.786 ------------------------
// double: fit error 2^-57.9; float: fit error 2^-28.0
inline constexpr double kSinD[6] = {-0x1.5555555555548p-3, 0x1.111111110f79ep-7, -0x1.a01a019bf773bp-13,
                                    0x1.71de356201bb1p-19, -0x1.ae5e55de1e1c2p-26, 0x1.5d8e6aa67dce6p-33};
inline constexpr float kSinF[3] = {-0x1.555546p-3f, 0x1.110734p-7f, -0x1.994134p-13f};

// --- cos: cos(r) ~ 1 - r^2/2 + r^4 * C(r^2), |r| <= 0.786 ----------------
// double: fit error 2^-63.9; float: fit error 2^-33.0
inline constexpr double kCosD[6] = {0x1.555555555554bp-5, -0x1.6c16c16c14f58p-10, 0x1.a01a019c7e991p-16,
                                    -0x1.27e4f7e6894d0p-22, 0x1.1ee9d4c2b4090p-29, -0x1.8fa30aa8294d3p-37};
inline constexpr float kCosF[3] = {0x1.55554ap-5f, -0x1.6c0c2cp-10f, 0x1.99e92ap-16f};

// --- atan: atan(t) ~ t + t^3 * A(t^2), |t| <= 0.4143 (> tan(pi/8)) ---------
// double: fit error 2^-59.4; float: fit error 2^-30.5
inline constexpr double kAtanD[11] = {
    -0x1.555555555553dp-2, 0x1.999999999578dp-3, -0x1.24924922a8a53p-3, 0x1.c71c70e46126ep-4,
    -0x1.745cf8af4c1eep-4, 0x1.3b1116233b602p-4, -0x1.10eb97e5d89c8p-4, 0x1.df0d844a6d372p-5,
    -0x1.9ccaf6449879bp-5, 0x1.37c25ddfedacbp-5, -0x1.2541002aa775cp-6};
inline constexpr float kAtanF[5] = {-0x1.55554ap-2f, 0x1.999194p-3f, -0x1.23b4e4p-3f, 0x1.b1e866p-4f,
                                    -0x1.f1d95ep-5f};

// --- tanh: tanh(x) ~ x + x^3 * T(x^2), |x| <= 0.5494 (> atanh(1/2)) -------
// double: fit error 2^-60.6; float: fit error 2^-29.9
inline constexpr double kTanhD[11] = {
    -0x1.555555555554fp-2, 0x1.11111111107cfp-3, -0x1.ba1ba1b980624p-5, 0x1.664f485a18b14p-6,
    -0x1.226e2f2aa1cc4p-7, 0x1.d6d29f2ffa24ap-9, -0x1.7d900353eeb17p-10, 0x1.34854181e60aep-11,
    -0x1.e9803953f2ab7p-13, 0x1.5da4bef0e7855p-14, -0x1.478b96053f2e7p-16};
inline constexpr float kTanhF[5] = {-0x1.55554ap-2f, 0x1.110d2ep-3f, -0x1.b929e8p-5f, 0x1.5949a2p-6f,
                                    -0x1.9b7c2cp-8f};

// --- reduction constants ---------------------------------------------------
inline constexpr double kLog2eD = 0x1.71547652b82fep+0;
inline constexpr double kLn2HiD = 0x1.62e42fefa3800p-1;  // 42 significant bits: k*hi exact, |k| < 2^11
inline constexpr double kLn2LoD = 0x1.ef35793c76730p-45;
inline constexpr float kLog2eF = 0x1.715476p+0f;
inline constexpr float kLn2HiF = 0x1.62e4p-1f;  // 16 significant bits: k*hi exact, |k| < 2^8
inline constexpr float kLn2LoF = 0x1.7f7d1cp-20f;

inline constexpr double kTwoOverPiD = 0x1.45f306dc9c883p-1;
// pi/2 = P1 + P2 + P3 + P4; P1..P3 have 33 significant bits so k*Pi is exact
// for k < 2^20 (Cody-Waite, docs/numerics.md#sin-cos).
inline constexpr double kPio2P1 = 0x1.921fb544p+0;
inline constexpr double kPio2P2 = 0x1.0b4611a6p-34;
inline constexpr double kPio2P3 = 0x1.3198a2ep-69;
inline constexpr double kPio2P4 = 0x1.b839a252049c1p-104;

inline constexpr double kPio4HiD = 0x1.921fb54442d18p-1, kPio4LoD = 0x1.1a62633145c07p-55;
inline constexpr double kPio2HiD = 0x1.921fb54442d18p+0, kPio2LoD = 0x1.1a62633145c07p-54;
inline constexpr float kPio4HiF = 0x1.921fb6p-1f, kPio4LoF = -0x1.777a5cp-26f;
inline constexpr float kPio2HiF = 0x1.921fb6p+0f, kPio2LoF = -0x1.777a5cp-25f;

// 2/pi as a bit string, 32 bits per word, first word = bits 2^-1 .. 2^-32
// (truncated), 1280 bits: enough for Payne-Hanek reduction of every finite
// double (docs/numerics.md#sin-cos).
inline constexpr std::uint32_t kTwoOverPiBits[40] = {
    0xa2f9836e, 0x4e441529, 0xfc2757d1, 0xf534ddc0, 0xdb629599, 0x3c439041,
    0xfe5163ab, 0xdebbc561, 0xb7246e3a, 0x424dd2e0, 0x06492eea, 0x09d1921c,
    0xfe1deb1c, 0xb129a73e, 0xe88235f5, 0x2ebb4484, 0xe99c7026, 0xb45f7e41,
    0x3991d639, 0x835339f4, 0x9c845f8b, 0xbdf9283b, 0x1ff897ff, 0xde05980f,
    0xef2f118b, 0x5a0a6d1f, 0x6d367ecf, 0x27cb09b7, 0x4f463f66, 0x9e5fea2d,
    0x7527bac7, 0xebe5f17b, 0x3d0739f7, 0x8a5292ea, 0x6bfb5fb1, 0x1f8d5d08,
    0x56033046, 0xfc7b6bab, 0xf0cfbc20, 0x9af4361d};
// round(pi/2 * 2^127) as two 64-bit halves
inline constexpr std::uint64_t kPio2Q127Hi = 0xc90fdaa22168c234u;
inline constexpr std::uint64_t kPio2Q127Lo = 0xc4c6628b80dc1cd1u;
inline constexpr std::uint64_t kPio2Q63 = 0xc90fdaa22168c235u;  // round(pi/2 * 2^63)

// --- fixed-point internals (Q60 = value * 2^60 in int64) ---------------------
inline constexpr std::int64_t kPio2Q60 = 0x1921fb54442d1847;
inline constexpr std::int64_t kTwoOverPiQ62 = 0x28be60db9391054a;
inline constexpr std::int64_t kLn2Q56 = 0xb17217f7d1cf7a;
inline constexpr std::int64_t kInvLn2Q60 = 0x171547652b82fe17;
// round(2^60 / n!), n = 0..19
inline constexpr std::int64_t kInvFactQ60[20] = {
    0x1000000000000000, 0x1000000000000000, 0x800000000000000, 0x2aaaaaaaaaaaaab, 0xaaaaaaaaaaaaab,
    0x22222222222222,   0x5b05b05b05b06,    0xd00d00d00d01,    0x1a01a01a01a0,    0x2e3bc74aad9,
    0x49f93edde2,       0x6b99159fd,        0x8f76c780,        0xb09230a,         0xc9cba5,
    0xd73fa,            0xd740,             0xca9,             0xb4,              0x9};
// round(atan(2^-i) * 2^61), i = 0..61 (CORDIC)
inline constexpr std::int64_t kAtan2iQ61[62] = {
    0x1921fb54442d1847, 0xed63382b0dda7b4, 0x7d6dd7e4b203759, 0x3fab7535585edb9, 0x1ff55bb72cfde9c,
    0xffeaaddd4bb125,   0x7ffd556eedca6b,  0x3fffaaab77752e,  0x1ffff5555bbbb7,  0xffffeaaaaddde,
    0x7ffffd55556ef,    0x3fffffaaaaab7,   0x1ffffff555556,   0xffffffeaaaab,    0x7ffffffd5555,
    0x3fffffffaaab,     0x1ffffffff555,    0xffffffffeab,     0x7ffffffffd5,     0x3fffffffffb,
    0x1ffffffffff,      0x10000000000,     0x8000000000,      0x4000000000,      0x2000000000,
    0x1000000000,       0x800000000,       0x400000000,       0x200000000,       0x100000000,
    0x80000000,         0x40000000,        0x20000000,        0x10000000,        0x8000000,
    0x4000000,          0x2000000,         0x1000000,         0x800000,          0x400000,
    0x200000,           0x100000,          0x80000,           0x40000,           0x20000,
    0x10000,            0x8000,            0x4000,            0x2000,            0x1000,
    0x800,              0x400,             0x200,             0x100,             0x80,
    0x40,               0x20,              0x10,              0x8,               0x4,
    0x2,                0x1};

}  // namespace cvt::dm::detail
