//! Every text loader on arbitrary bytes: errors are fine, panics are not; whatever loads
//! must be a valid domain that triangulates.
#![no_main]

use libfuzzer_sys::fuzz_target;
use stopscan::io::{bench_format, text_formats};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let results = [
        bench_format::parse(text, "fuzz").map(|e| e.domain),
        text_formats::parse_geojson(text, "fuzz").map(|e| e.domain),
        text_formats::parse_wkt(text, "fuzz").map(|e| e.domain),
        text_formats::parse_pol(text, "fuzz").map(|e| e.domain),
    ];
    for d in results.into_iter().flatten() {
        // The float area of a sliver with huge coordinates can round to 0; it must stay finite.
        assert!(d.area().is_finite());
        let _ = stopscan::algorithm::visibility::Visibility::new(d)
            .expect("a valid domain triangulates");
    }
});
