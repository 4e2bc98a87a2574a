//! A minimal encoder and decoder for little-endian OMG CDR (XCDR1, "CDR_LE"), the
//! `cdr` message encoding of MCAP and ROS 2.
//!
//! Only what carom's messages use: integers, `float64`, strings, sequences (`T[]`,
//! a `uint32` length then the elements) and fixed arrays (`T[n]`) of them. Every
//! buffer starts with the encapsulation header `00 01 00 00`; every primitive is
//! aligned to its own size, counted from the end of that header. The bulk encoder
//! appends whole arrays into a reused `Vec<u8>` (the `mcap_python` test checks its
//! layout against Python's decoder; docs/performance.md, "CDR codec"). The decoder
//! checks every length against the bytes left before allocating, so corrupted input
//! gives a [`CdrError`], never a panic or a huge allocation.

use thiserror::Error;

/// The encapsulation header of little-endian plain CDR.
pub const CDR_LE_HEADER: [u8; 4] = [0x00, 0x01, 0x00, 0x00];

/// A CDR buffer that could not be decoded.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum CdrError {
    /// The buffer does not start with the little-endian CDR header.
    #[error("not little-endian CDR: encapsulation header {0:02x?} (expected 00 01 00 00)")]
    BadHeader(Vec<u8>),
    /// The buffer ended before field `field` was complete.
    #[error("CDR data ends inside field `{field}` (needed {needed} more bytes at offset {offset}, {available} left)")]
    Truncated {
        /// Name of the field being read.
        field: &'static str,
        /// Byte offset (from the start of the buffer) where the read started.
        offset: usize,
        /// Bytes the read needed.
        needed: usize,
        /// Bytes that were left.
        available: usize,
    },
    /// A field holds a value the message does not allow.
    #[error("CDR field `{field}`: {problem}")]
    Invalid {
        /// Name of the field.
        field: &'static str,
        /// What is wrong with it.
        problem: String,
    },
}

/// Appends CDR_LE data to a byte buffer. Reuse one writer (see [`CdrWriter::reset`])
/// to encode many messages without allocating.
#[derive(Debug, Default, Clone)]
pub struct CdrWriter {
    buf: Vec<u8>,
}

/// A primitive with a little-endian byte form, as CDR stores it.
pub trait CdrPrimitive: Copy {
    /// Size in bytes (also the CDR alignment).
    const SIZE: usize;
    /// Append the little-endian bytes of `self`.
    fn put(self, out: &mut Vec<u8>);
    /// Read from exactly `SIZE` little-endian bytes.
    fn get(bytes: &[u8]) -> Self;
}

macro_rules! primitive {
    ($t:ty, $n:expr) => {
        impl CdrPrimitive for $t {
            const SIZE: usize = $n;
            #[inline(always)]
            fn put(self, out: &mut Vec<u8>) {
                out.extend_from_slice(&self.to_le_bytes());
            }
            #[inline(always)]
            fn get(bytes: &[u8]) -> Self {
                let mut a = [0u8; $n];
                a.copy_from_slice(&bytes[..$n]);
                <$t>::from_le_bytes(a)
            }
        }
    };
}
primitive!(u8, 1);
primitive!(u16, 2);
primitive!(u32, 4);
primitive!(i32, 4);
primitive!(u64, 8);
primitive!(f64, 8);

impl CdrWriter {
    /// A writer holding only the encapsulation header.
    pub fn new() -> Self {
        let mut w = CdrWriter { buf: Vec::new() };
        w.reset();
        w
    }

    /// Forget the content (keeping the allocation) and write the header again.
    pub fn reset(&mut self) {
        self.buf.clear();
        self.buf.extend_from_slice(&CDR_LE_HEADER);
    }

    /// The encoded bytes so far (header included).
    pub fn bytes(&self) -> &[u8] {
        &self.buf
    }

    /// Take the encoded bytes.
    pub fn into_bytes(self) -> Vec<u8> {
        self.buf
    }

    /// Take the encoded bytes, leaving the writer empty (call
    /// [`CdrWriter::reset`] before writing again): no copy of a large message.
    pub fn take_bytes(&mut self) -> Vec<u8> {
        std::mem::take(&mut self.buf)
    }

    /// Write into `buf`'s allocation from now on (its contents are dropped) if it
    /// is larger than the writer's own; call [`CdrWriter::reset`] before writing.
    pub fn reuse(&mut self, mut buf: Vec<u8>) {
        if buf.capacity() > self.buf.capacity() {
            buf.clear();
            self.buf = buf;
        }
    }

    /// Reserve room for `additional` more bytes.
    pub fn reserve(&mut self, additional: usize) {
        self.buf.reserve(additional);
    }

    #[inline]
    fn align(&mut self, size: usize) {
        let pos = self.buf.len() - 4;
        let pad = (size - pos % size) % size;
        self.buf.resize(self.buf.len() + pad, 0);
    }

    /// Append one primitive, aligned.
    #[inline]
    pub fn put<T: CdrPrimitive>(&mut self, v: T) {
        self.align(T::SIZE);
        v.put(&mut self.buf);
    }

    /// Append a sequence `T[]`: aligned `uint32` length, then the elements.
    pub fn seq<T: CdrPrimitive>(&mut self, values: &[T]) {
        let n = u32::try_from(values.len()).expect("CDR sequences hold at most 2^32 - 1 elements");
        self.put(n);
        self.array(values);
    }

    /// Append a fixed-size array `T[n]` (no length prefix).
    pub fn array<T: CdrPrimitive>(&mut self, values: &[T]) {
        if values.is_empty() {
            return;
        }
        self.align(T::SIZE);
        self.buf.reserve(values.len() * T::SIZE);
        for &v in values {
            v.put(&mut self.buf);
        }
    }

    /// Append a `string`: aligned `uint32` length counting a terminating NUL, the
    /// UTF-8 bytes, then the NUL.
    pub fn string(&mut self, s: &str) {
        let n = u32::try_from(s.len() + 1).expect("CDR strings hold at most 2^32 - 2 bytes");
        self.put(n);
        self.buf.extend_from_slice(s.as_bytes());
        self.buf.push(0);
    }

    /// Append a sequence whose elements come from an iterator of known length.
    pub fn seq_iter<T: CdrPrimitive, I: ExactSizeIterator<Item = T>>(&mut self, values: I) {
        let n = u32::try_from(values.len()).expect("CDR sequences hold at most 2^32 - 1 elements");
        self.put(n);
        if n == 0 {
            return;
        }
        self.align(T::SIZE);
        self.buf.reserve(n as usize * T::SIZE);
        for v in values {
            v.put(&mut self.buf);
        }
    }
}

/// Reads CDR_LE data, checking every bound.
#[derive(Debug, Clone)]
pub struct CdrReader<'a> {
    data: &'a [u8],
    pos: usize,
}

impl<'a> CdrReader<'a> {
    /// Start reading `data`, which must begin with the little-endian CDR header.
    pub fn new(data: &'a [u8]) -> Result<Self, CdrError> {
        if data.len() < 4 || data[..2] != CDR_LE_HEADER[..2] {
            return Err(CdrError::BadHeader(data[..data.len().min(4)].to_vec()));
        }
        Ok(CdrReader { data, pos: 4 })
    }

    /// Bytes not yet read (after the current position).
    pub fn remaining(&self) -> usize {
        self.data.len() - self.pos
    }

    fn align(&mut self, size: usize) {
        let rel = self.pos - 4;
        let pad = (size - rel % size) % size;
        self.pos = (self.pos + pad).min(self.data.len());
    }

    fn take(&mut self, field: &'static str, n: usize) -> Result<&'a [u8], CdrError> {
        if self.remaining() < n {
            return Err(CdrError::Truncated {
                field,
                offset: self.pos,
                needed: n,
                available: self.remaining(),
            });
        }
        let s = &self.data[self.pos..self.pos + n];
        self.pos += n;
        Ok(s)
    }

    /// Step over `n` aligned primitives of type `T` without reading them.
    pub fn skip<T: CdrPrimitive>(&mut self, field: &'static str, n: usize) -> Result<(), CdrError> {
        self.align(T::SIZE);
        let bytes = n.checked_mul(T::SIZE).ok_or(CdrError::Truncated {
            field,
            offset: self.pos,
            needed: usize::MAX,
            available: self.remaining(),
        })?;
        self.take(field, bytes).map(|_| ())
    }

    /// Read one aligned primitive.
    pub fn get<T: CdrPrimitive>(&mut self, field: &'static str) -> Result<T, CdrError> {
        self.align(T::SIZE);
        Ok(T::get(self.take(field, T::SIZE)?))
    }

    /// Read a sequence `T[]` into `out` (cleared first; its allocation is reused).
    pub fn seq_into<T: CdrPrimitive>(
        &mut self,
        field: &'static str,
        out: &mut Vec<T>,
    ) -> Result<(), CdrError> {
        let n = self.get::<u32>(field)? as usize;
        self.array_into(field, n, out)
    }

    /// Read a `string` (length with its terminating NUL, bytes, NUL).
    pub fn string(&mut self, field: &'static str) -> Result<String, CdrError> {
        let n = self.get::<u32>(field)? as usize;
        let raw = self.take(field, n)?;
        match raw.split_last() {
            Some((0, text)) => String::from_utf8(text.to_vec()).map_err(|e| CdrError::Invalid {
                field,
                problem: format!("not UTF-8: {e}"),
            }),
            _ => Err(CdrError::Invalid {
                field,
                problem: "string without its terminating NUL".into(),
            }),
        }
    }

    /// Read a sequence `T[]`.
    pub fn seq<T: CdrPrimitive>(&mut self, field: &'static str) -> Result<Vec<T>, CdrError> {
        let mut v = Vec::new();
        self.seq_into(field, &mut v)?;
        Ok(v)
    }

    /// Read a fixed-size array `T[n]` into `out` (cleared first).
    pub fn array_into<T: CdrPrimitive>(
        &mut self,
        field: &'static str,
        n: usize,
        out: &mut Vec<T>,
    ) -> Result<(), CdrError> {
        out.clear();
        if n == 0 {
            return Ok(());
        }
        self.align(T::SIZE);
        let bytes = n.checked_mul(T::SIZE).ok_or_else(|| CdrError::Invalid {
            field,
            problem: format!("length {n} overflows"),
        })?;
        let raw = self.take(field, bytes)?;
        out.reserve(n);
        out.extend(raw.chunks_exact(T::SIZE).map(T::get));
        Ok(())
    }

    /// Read a fixed-size array `T[N]`.
    pub fn fixed<T: CdrPrimitive + Default, const N: usize>(
        &mut self,
        field: &'static str,
    ) -> Result<[T; N], CdrError> {
        let mut out = [T::default(); N];
        if N == 0 {
            return Ok(out);
        }
        self.align(T::SIZE);
        let raw = self.take(field, N * T::SIZE)?;
        for (o, c) in out.iter_mut().zip(raw.chunks_exact(T::SIZE)) {
            *o = T::get(c);
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layout_matches_cdr_alignment_rules() {
        let mut w = CdrWriter::new();
        w.put(7u8);
        w.put(1.5f64);
        w.seq(&[1u8, 2, 3]);
        w.seq(&[2.0f64]);
        let b = w.bytes();
        assert_eq!(&b[..4], &CDR_LE_HEADER);
        // u8 at 4, pad to 8 (relative 4 → 8 relative = absolute 12)
        assert_eq!(b[4], 7);
        assert_eq!(&b[12..20], &1.5f64.to_le_bytes());
        assert_eq!(&b[20..24], &3u32.to_le_bytes());
        assert_eq!(&b[24..27], &[1, 2, 3]);
        // u32 length aligned to 4 relative: rel 23 → 24 → absolute 28
        assert_eq!(&b[28..32], &1u32.to_le_bytes());
        // f64 aligned to 8 relative: rel 28 → 32 → absolute 36
        assert_eq!(&b[36..44], &2.0f64.to_le_bytes());
        assert_eq!(b.len(), 44);

        let mut r = CdrReader::new(b).unwrap();
        assert_eq!(r.get::<u8>("a").unwrap(), 7);
        assert_eq!(r.get::<f64>("b").unwrap(), 1.5);
        assert_eq!(r.seq::<u8>("c").unwrap(), vec![1, 2, 3]);
        assert_eq!(r.seq::<f64>("d").unwrap(), vec![2.0]);
        assert_eq!(r.remaining(), 0);
    }

    #[test]
    fn taken_bytes_are_the_message_and_the_writer_starts_again_after_reset() {
        let mut w = CdrWriter::new();
        w.put(3u32);
        let expected = w.bytes().to_vec();
        assert_eq!(w.take_bytes(), expected);
        assert!(w.bytes().is_empty());
        w.reset();
        w.put(4u32);
        assert_eq!(
            w.bytes(),
            [&CDR_LE_HEADER[..], &4u32.to_le_bytes()].concat()
        );
    }

    #[test]
    fn corrupted_lengths_are_errors_not_allocations() {
        let mut w = CdrWriter::new();
        w.seq(&[1.0f64, 2.0]);
        let mut b = w.into_bytes();
        b[4..8].copy_from_slice(&u32::MAX.to_le_bytes());
        let mut r = CdrReader::new(&b).unwrap();
        assert!(matches!(
            r.seq::<f64>("x"),
            Err(CdrError::Truncated { field: "x", .. })
        ));
        assert!(matches!(
            CdrReader::new(&[0, 0, 0, 0]),
            Err(CdrError::BadHeader(_))
        ));
        assert!(matches!(CdrReader::new(&[0]), Err(CdrError::BadHeader(_))));
    }

    #[test]
    fn strings_carry_their_nul_and_align_their_length() {
        let mut w = CdrWriter::new();
        w.put(1u8);
        w.string("box");
        w.put(-2i32);
        let b = w.bytes();
        // u8 at 4, length aligned to relative 4 (absolute 8): 4 = "box" + NUL.
        assert_eq!(&b[8..12], &4u32.to_le_bytes());
        assert_eq!(&b[12..16], b"box\0");
        assert_eq!(&b[16..20], &(-2i32).to_le_bytes());
        let mut r = CdrReader::new(b).unwrap();
        assert_eq!(r.get::<u8>("a").unwrap(), 1);
        assert_eq!(r.string("s").unwrap(), "box");
        assert_eq!(r.get::<i32>("i").unwrap(), -2);
        let mut bad = b.to_vec();
        bad[15] = b'x';
        let mut r = CdrReader::new(&bad).unwrap();
        r.get::<u8>("a").unwrap();
        assert!(matches!(
            r.string("s"),
            Err(CdrError::Invalid { field: "s", .. })
        ));
    }
}
