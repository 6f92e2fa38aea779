//! A serde value tree that keeps every f64 as it is (NaN, infinities and -0 included), for the
//! payload of a serialized FMU state: `serde_json::Value` turns non-finite floats into `null`.
//! [`to_tree`] serializes any value into a [`Tree`]; a [`Tree`] is a deserializer of any value.
//! Enums with data are not supported (the run state has none); unit variants are strings.

use std::fmt;

use serde::de::value::{MapDeserializer, SeqDeserializer};
use serde::de::{self, IntoDeserializer, Visitor};
use serde::{ser, Serialize};

/// A serialized value: JSON's data model with integers and floats kept apart.
#[derive(Clone, Debug, PartialEq)]
pub enum Tree {
    /// `None`, `()` and unit structs.
    Null,
    /// A bool.
    Bool(bool),
    /// An unsigned integer.
    U64(u64),
    /// A signed integer.
    I64(i64),
    /// A float, bit for bit.
    F64(f64),
    /// A string (also chars and unit variants).
    Str(String),
    /// Sequences and tuples.
    Seq(Vec<Tree>),
    /// Structs and maps with string keys, in serialization order.
    Map(Vec<(String, Tree)>),
}

/// Why a value could not be turned into a tree or read back from one.
#[derive(Debug)]
pub struct TreeError(String);

impl fmt::Display for TreeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for TreeError {}

impl ser::Error for TreeError {
    fn custom<T: fmt::Display>(msg: T) -> Self {
        TreeError(msg.to_string())
    }
}

impl de::Error for TreeError {
    fn custom<T: fmt::Display>(msg: T) -> Self {
        TreeError(msg.to_string())
    }
}

type Built = Result<Tree, TreeError>;

/// Serializes `value` into a [`Tree`].
pub fn to_tree<T: Serialize + ?Sized>(value: &T) -> Built {
    value.serialize(Builder)
}

fn unsupported(what: &str) -> TreeError {
    TreeError(format!("{what} is not supported in an FMU state"))
}

/// The serializer behind [`to_tree`].
struct Builder;

/// Collects the elements of a sequence or tuple.
struct SeqBuilder(Vec<Tree>);

/// Collects the fields of a struct or the entries of a map.
struct MapBuilder {
    entries: Vec<(String, Tree)>,
    key: Option<String>,
}

impl ser::Serializer for Builder {
    type Ok = Tree;
    type Error = TreeError;
    type SerializeSeq = SeqBuilder;
    type SerializeTuple = SeqBuilder;
    type SerializeTupleStruct = SeqBuilder;
    type SerializeTupleVariant = ser::Impossible<Tree, TreeError>;
    type SerializeMap = MapBuilder;
    type SerializeStruct = MapBuilder;
    type SerializeStructVariant = ser::Impossible<Tree, TreeError>;

    fn serialize_bool(self, v: bool) -> Built {
        Ok(Tree::Bool(v))
    }
    fn serialize_i8(self, v: i8) -> Built {
        Ok(Tree::I64(v.into()))
    }
    fn serialize_i16(self, v: i16) -> Built {
        Ok(Tree::I64(v.into()))
    }
    fn serialize_i32(self, v: i32) -> Built {
        Ok(Tree::I64(v.into()))
    }
    fn serialize_i64(self, v: i64) -> Built {
        Ok(Tree::I64(v))
    }
    fn serialize_u8(self, v: u8) -> Built {
        Ok(Tree::U64(v.into()))
    }
    fn serialize_u16(self, v: u16) -> Built {
        Ok(Tree::U64(v.into()))
    }
    fn serialize_u32(self, v: u32) -> Built {
        Ok(Tree::U64(v.into()))
    }
    fn serialize_u64(self, v: u64) -> Built {
        Ok(Tree::U64(v))
    }
    fn serialize_f32(self, v: f32) -> Built {
        Ok(Tree::F64(v.into()))
    }
    fn serialize_f64(self, v: f64) -> Built {
        Ok(Tree::F64(v))
    }
    fn serialize_char(self, v: char) -> Built {
        Ok(Tree::Str(v.to_string()))
    }
    fn serialize_str(self, v: &str) -> Built {
        Ok(Tree::Str(v.to_string()))
    }
    fn serialize_bytes(self, v: &[u8]) -> Built {
        Ok(Tree::Seq(v.iter().map(|&b| Tree::U64(b.into())).collect()))
    }
    fn serialize_none(self) -> Built {
        Ok(Tree::Null)
    }
    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Built {
        value.serialize(self)
    }
    fn serialize_unit(self) -> Built {
        Ok(Tree::Null)
    }
    fn serialize_unit_struct(self, _name: &'static str) -> Built {
        Ok(Tree::Null)
    }
    fn serialize_unit_variant(self, _name: &'static str, _index: u32, variant: &'static str) -> Built {
        Ok(Tree::Str(variant.to_string()))
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(self, _name: &'static str, value: &T) -> Built {
        value.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        name: &'static str,
        _index: u32,
        variant: &'static str,
        _value: &T,
    ) -> Built {
        Err(unsupported(&format!("the enum variant {name}::{variant}")))
    }
    fn serialize_seq(self, len: Option<usize>) -> Result<SeqBuilder, TreeError> {
        Ok(SeqBuilder(Vec::with_capacity(len.unwrap_or(0))))
    }
    fn serialize_tuple(self, len: usize) -> Result<SeqBuilder, TreeError> {
        Ok(SeqBuilder(Vec::with_capacity(len)))
    }
    fn serialize_tuple_struct(self, _name: &'static str, len: usize) -> Result<SeqBuilder, TreeError> {
        Ok(SeqBuilder(Vec::with_capacity(len)))
    }
    fn serialize_tuple_variant(
        self,
        name: &'static str,
        _index: u32,
        variant: &'static str,
        _len: usize,
    ) -> Result<Self::SerializeTupleVariant, TreeError> {
        Err(unsupported(&format!("the enum variant {name}::{variant}")))
    }
    fn serialize_map(self, len: Option<usize>) -> Result<MapBuilder, TreeError> {
        Ok(MapBuilder { entries: Vec::with_capacity(len.unwrap_or(0)), key: None })
    }
    fn serialize_struct(self, _name: &'static str, len: usize) -> Result<MapBuilder, TreeError> {
        Ok(MapBuilder { entries: Vec::with_capacity(len), key: None })
    }
    fn serialize_struct_variant(
        self,
        name: &'static str,
        _index: u32,
        variant: &'static str,
        _len: usize,
    ) -> Result<Self::SerializeStructVariant, TreeError> {
        Err(unsupported(&format!("the enum variant {name}::{variant}")))
    }
}

impl ser::SerializeSeq for SeqBuilder {
    type Ok = Tree;
    type Error = TreeError;
    fn serialize_element<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), TreeError> {
        self.0.push(value.serialize(Builder)?);
        Ok(())
    }
    fn end(self) -> Built {
        Ok(Tree::Seq(self.0))
    }
}

impl ser::SerializeTuple for SeqBuilder {
    type Ok = Tree;
    type Error = TreeError;
    fn serialize_element<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), TreeError> {
        ser::SerializeSeq::serialize_element(self, value)
    }
    fn end(self) -> Built {
        ser::SerializeSeq::end(self)
    }
}

impl ser::SerializeTupleStruct for SeqBuilder {
    type Ok = Tree;
    type Error = TreeError;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), TreeError> {
        ser::SerializeSeq::serialize_element(self, value)
    }
    fn end(self) -> Built {
        ser::SerializeSeq::end(self)
    }
}

impl ser::SerializeMap for MapBuilder {
    type Ok = Tree;
    type Error = TreeError;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), TreeError> {
        match key.serialize(Builder)? {
            Tree::Str(k) => self.key = Some(k),
            other => return Err(TreeError(format!("map key {other:?} is not a string"))),
        }
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), TreeError> {
        let key = self.key.take().ok_or_else(|| TreeError("map value without a key".into()))?;
        self.entries.push((key, value.serialize(Builder)?));
        Ok(())
    }
    fn end(self) -> Built {
        Ok(Tree::Map(self.entries))
    }
}

impl ser::SerializeStruct for MapBuilder {
    type Ok = Tree;
    type Error = TreeError;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, key: &'static str, value: &T) -> Result<(), TreeError> {
        self.entries.push((key.to_string(), value.serialize(Builder)?));
        Ok(())
    }
    fn end(self) -> Built {
        Ok(Tree::Map(self.entries))
    }
}

impl<'de> de::Deserializer<'de> for Tree {
    type Error = TreeError;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, TreeError> {
        match self {
            Tree::Null => visitor.visit_unit(),
            Tree::Bool(b) => visitor.visit_bool(b),
            Tree::U64(n) => visitor.visit_u64(n),
            Tree::I64(n) => visitor.visit_i64(n),
            Tree::F64(x) => visitor.visit_f64(x),
            Tree::Str(s) => visitor.visit_string(s),
            Tree::Seq(items) => {
                let mut seq = SeqDeserializer::new(items.into_iter());
                let value = visitor.visit_seq(&mut seq)?;
                seq.end()?;
                Ok(value)
            }
            Tree::Map(entries) => {
                let mut map = MapDeserializer::new(entries.into_iter());
                let value = visitor.visit_map(&mut map)?;
                map.end()?;
                Ok(value)
            }
        }
    }

    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, TreeError> {
        match self {
            Tree::Null => visitor.visit_none(),
            other => visitor.visit_some(other),
        }
    }

    fn deserialize_newtype_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        visitor: V,
    ) -> Result<V::Value, TreeError> {
        visitor.visit_newtype_struct(self)
    }

    fn deserialize_enum<V: Visitor<'de>>(
        self,
        name: &'static str,
        _variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, TreeError> {
        match self {
            Tree::Str(variant) => visitor.visit_enum(variant.into_deserializer()),
            other => Err(TreeError(format!("{other:?} is not a unit variant of {name}"))),
        }
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf unit
        unit_struct seq tuple tuple_struct map struct identifier ignored_any
    }
}

impl<'de> IntoDeserializer<'de, TreeError> for Tree {
    type Deserializer = Tree;
    fn into_deserializer(self) -> Tree {
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Deserialize;

    #[derive(Debug, PartialEq, Serialize, Deserialize)]
    enum Side {
        Upper,
        Lower,
    }

    #[derive(Debug, PartialEq, Serialize, Deserialize)]
    struct Sample {
        x: f64,
        n: u64,
        k: i32,
        name: String,
        maybe: Option<f64>,
        none: Option<u8>,
        list: Vec<(f64, bool)>,
        side: Side,
        unit: (),
    }

    #[test]
    fn every_value_round_trips_floats_bit_for_bit() {
        let sample = Sample {
            x: f64::from_bits(0x7ff8_0000_0000_beef),
            n: u64::MAX,
            k: -3,
            name: "3ff0000000000000".into(),
            maybe: Some(-0.0),
            none: None,
            list: vec![(f64::INFINITY, true), (1.5, false)],
            side: Side::Lower,
            unit: (),
        };
        let tree = to_tree(&sample).unwrap();
        let back = Sample::deserialize(tree.clone()).unwrap();
        assert_eq!(back.x.to_bits(), sample.x.to_bits());
        assert_eq!(back.maybe.map(f64::to_bits), Some((-0.0f64).to_bits()));
        assert_eq!(
            (back.n, back.k, &back.name, back.none, &back.side),
            (u64::MAX, -3, &sample.name, None, &Side::Lower)
        );
        assert_eq!(back.list[0].0, f64::INFINITY);
        assert!(matches!(tree, Tree::Map(ref fields) if fields[0].0 == "x"));
        let _ = Side::Upper;
    }
}
