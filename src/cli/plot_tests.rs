//! Tests of the figures at the data level: each is drawn to SVG and its text
//! (tick labels, legend entries, captions) read back.
