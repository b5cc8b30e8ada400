//! Numbers in messages kept short: Rust prints an `f64` with `{}` in full
//! decimal (`1e-300` as 300 zeros and a 1), so a message that echoes an
//! absurd value the user gave would bury it.

use std::borrow::Cow;

/// Digits a number printed in full decimal may have before it is shown in
/// scientific notation: more than any integer count or id (`u64::MAX` has
/// 20), so only floats far from 1 are rewritten.
const LONGEST: usize = 21;

/// `message` with every run of digits (with at most one decimal point)
/// longer than [`LONGEST`] digits rewritten in scientific notation, as
/// `{:e}` prints the same `f64` (`0.000…0001` → `1e-300`,
/// `1000…000` → `1e300`). Rust's `{}` prints the shortest decimal that
/// reads back to the same `f64`, so the value shown is the value held.
pub fn shortened(message: &str) -> Cow<'_, str> {
    let is_part = |c: char| c.is_ascii_digit() || c == '.';
    let long = |run: &str| run.bytes().filter(u8::is_ascii_digit).count() > LONGEST;
    if !message.split(|c: char| !is_part(c)).any(long) {
        return Cow::Borrowed(message);
    }
    let mut out = String::with_capacity(message.len());
    let mut rest = message;
    while let Some(start) = rest.find(is_part) {
        out.push_str(&rest[..start]);
        rest = &rest[start..];
        let end = rest.find(|c: char| !is_part(c)).unwrap_or(rest.len());
        // A sentence's full stop after the number is not part of it (and
        // a run of full stops alone is copied as it is).
        let run = match rest[..end].trim_end_matches('.') {
            "" => &rest[..end],
            run => run,
        };
        match run.parse::<f64>() {
            Ok(x) if long(run) && x.is_finite() => out.push_str(&format!("{x:e}")),
            _ => out.push_str(run),
        }
        rest = &rest[run.len()..];
    }
    out.push_str(rest);
    Cow::Owned(out)
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::shortened;

    proptest! {
        /// Any text of digits, points and words without long numbers comes
        /// back as it was, and a huge number put in one is rewritten.
        #[test]
        fn any_text_is_kept_but_its_long_numbers(text in "[0-9. a-z-]{0,80}", x in any::<f64>()) {
            let out = shortened(&text);
            let long = text.split(|c: char| !(c.is_ascii_digit() || c == '.'))
                .any(|r| r.bytes().filter(u8::is_ascii_digit).count() > 21);
            if !long {
                prop_assert_eq!(out.as_ref(), text.as_str());
            }
            let with = format!("{text} {x} {text}");
            let shown = shortened(&with);
            prop_assert!(shown.len() <= with.len());
            if x.is_finite() && x.abs() > 1e25 {
                prop_assert!(shown.contains(&format!("{x:e}")), "{}", shown);
            }
        }
    }

    #[test]
    fn long_numbers_are_shown_in_scientific_notation() {
        let tiny = format!("element_size: {} m.", 1e-300);
        assert!(tiny.len() > 300);
        assert_eq!(shortened(&tiny), "element_size: 1e-300 m.");
        assert_eq!(shortened(&format!("ratio = {}", 1e300)), "ratio = 1e300");
        assert_eq!(shortened(&format!("-{} Pa", 1.25e-30)), "-1.25e-30 Pa");
        assert_eq!(shortened(&format!("{}", 6.752001471527695e-152)), "6.752001471527695e-152");
    }

    #[test]
    fn ordinary_numbers_ids_and_versions_are_kept() {
        for kept in [
            "line 12, column 3: 2.5e6 Pa, 0.000123 s",
            "node 18446744073709551615 of 12 tets",
            "version 1.2.3; 3.141592653589793",
            "path out/a.b/12345678901234567890.vtu",
            "stops... and . . starts.",
        ] {
            assert_eq!(shortened(kept), kept);
        }
    }
}
