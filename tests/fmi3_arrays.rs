//! FMI 3 get/set with `nValues` through the exported functions: an array variable gives and
//! takes its elements row-major, equal to the FMI 2 scalars; a wrong `nValues`, an unknown
//! value reference, a variable of another type, `time` as a target and NaN are `fmi3Error`
//! with nothing changed; an array parameter is set before initialisation; the types without
//! variables accept only an empty list.

mod fmu_support;

use fmu_support::fmi3::*;
use fmu_support::*;
use triad::ffi::fmi3::getset::*;
use triad::ffi::fmi3::types::*;
use triad::ffi::getset::{fmi2GetInteger, fmi2GetReal};
use triad::ffi::types::fmi2OK;

/// The FMI 2 values of `vrs` on the same instance (an `fmi3Instance` is the same component).
fn fmi2_reals(f: &Fmu3, vrs: &[u32]) -> Vec<f64> {
    let mut out = vec![f64::NAN; vrs.len()];
    let s = unsafe { fmi2GetReal(f.c, vrs.as_ptr(), vrs.len(), out.as_mut_ptr()) };
    assert_eq!(s, fmi2OK);
    out
}

#[test]
fn a_rotation_matrix_is_nine_row_major_values_equal_to_the_fmi2_scalars() {
    let m = shipped("robot_arm");
    let f = Fmu3::initialised(&m);
    let (ins, n_in) = f.vrs(&m, triad::variables::Causality::Input);
    let u: Vec<f64> = (0..n_in).map(|i| 0.5 + i as f64).collect();
    for n in 0..20 {
        assert_eq!(f.set_f64(&ins, &u), fmi3OK);
        assert_eq!(f.step(n as f64 * 0.01, 0.01).0, fmi3OK);
    }
    let rot: Vec<_> =
        f.t3.vars
            .iter()
            .filter(|v| v.name.ends_with(".R") && v.dims == [3, 3])
            .cloned()
            .collect();
    assert!(!rot.is_empty());
    for r in &rot {
        let names: Vec<String> = r
            .members
            .iter()
            .map(|&vr| m.table.by_vr(vr).unwrap().name.clone())
            .collect();
        assert_eq!(names[1], format!("{}[1,2]", r.name), "row-major");
        assert_eq!(names[3], format!("{}[2,1]", r.name));
        let (s, got) = f.get_f64(&[r.vr], 9);
        assert_eq!(s, fmi3OK);
        assert_eq!(got, fmi2_reals(&f, &r.members), "{}", r.name);
    }
    // several variables at once: the values one after the other
    let r = f.var(&rot[0].name.replace(".R", ".r")).clone();
    assert_eq!(r.dims, [3]);
    let (s, got) = f.get_f64(&[rot[0].vr, 0, r.vr], 13);
    assert_eq!(s, fmi3OK);
    assert_eq!(got[..9], fmi2_reals(&f, &rot[0].members)[..]);
    assert_eq!(got[9], 0.2);
    assert_eq!(got[10..], fmi2_reals(&f, &r.members)[..]);
    // a wrong nValues: error, the output untouched
    for n in [8, 10, 0] {
        let (s, got) = f.get_f64(&[rot[0].vr], n);
        assert_eq!(s, fmi3Error, "nValues {n}");
        assert!(got.iter().all(|x| x.is_nan()));
        assert!(f.last_message().contains("nValues"), "{}", f.last_message());
    }
}

#[test]
fn an_array_parameter_is_set_before_initialisation() {
    let m = shipped("robot_arm");
    let f = Fmu3::new(&m);
    let g = f.var("gravity").clone();
    assert_eq!(g.dims, [3]);
    assert_eq!(
        f.set_f64(&[g.vr], &[0.1, -0.2, -9.7]),
        fmi3OK,
        "{:?}",
        f.messages()
    );
    // a wrong count, NaN or time: refused, nothing changed
    assert_eq!(f.set_f64(&[g.vr], &[1.0, 2.0]), fmi3Error);
    assert_eq!(f.set_f64(&[g.vr], &[1.0, 2.0, 3.0, 4.0]), fmi3Error);
    assert_eq!(f.set_f64(&[g.vr], &[1.0, f64::NAN, 3.0]), fmi3Error);
    assert_eq!(f.set_f64(&[g.vr, 0], &[1.0, 2.0, 3.0, 0.0]), fmi3Error);
    assert!(f.last_message().contains("time"), "{}", f.last_message());
    let bad = f.t3.vars.len() as u32 + 1;
    assert_eq!(f.set_f64(&[g.vr, bad], &[1.0, 2.0, 3.0, 4.0]), fmi3Error);
    assert!(f
        .last_message()
        .contains(&format!("unknown value reference {bad}")));
    // nValues given without values: refused
    let vr = [g.vr];
    assert_eq!(
        unsafe { fmi3SetFloat64(f.c, vr.as_ptr(), 1, std::ptr::null(), 0) },
        fmi3Error
    );
    assert_eq!(f.enter_init(0.0), fmi3OK);
    let (s, got) = f.get_f64(&[g.vr], 3);
    assert_eq!(s, fmi3OK);
    assert_eq!(got, [0.1, -0.2, -9.7]);
    assert_eq!(fmi2_reals(&f, &g.members), [0.1, -0.2, -9.7]);
    // an output cannot be set
    let out =
        f.t3.vars
            .iter()
            .find(|v| v.name.ends_with(".R"))
            .unwrap()
            .clone();
    assert_eq!(f.set_f64(&[out.vr], &[0.0; 9]), fmi3Error);
    // in Step Mode a fixed parameter is refused, nothing changed
    assert_eq!(
        unsafe { fmu_support::api3::fmi3ExitInitializationMode(f.c) },
        fmi3OK
    );
    assert_eq!(f.set_f64(&[g.vr], &[0.0, 0.0, -1.0]), fmi3Error);
    assert_eq!(f.get_f64(&[g.vr], 3).1, [0.1, -0.2, -9.7]);
}

#[test]
fn int32_is_the_integer_parameters_and_types_do_not_mix() {
    let m = shipped("robot_arm");
    let f = Fmu3::new(&m);
    let order = f.var("solver.order").clone();
    assert!(order.dims.is_empty());
    // Float64 of an Int32 variable and Int32 of a Float64 variable: unknown for that type
    let mut x = [0.0];
    let vr = [order.vr];
    assert_eq!(
        unsafe { fmi3GetFloat64(f.c, vr.as_ptr(), 1, x.as_mut_ptr(), 1) },
        fmi3Error
    );
    let g = [f.var("gravity").vr];
    let mut k = [0i32; 3];
    assert_eq!(
        unsafe { fmi3SetInt32(f.c, g.as_ptr(), 1, k.as_ptr(), 3) },
        fmi3Error
    );
    assert!(
        f.last_message().contains("for Int32"),
        "{}",
        f.last_message()
    );
    assert_eq!(
        unsafe { fmi3SetInt32(f.c, vr.as_ptr(), 1, [4].as_ptr(), 1) },
        fmi3OK
    );
    assert_eq!(f.enter_init(0.0), fmi3OK, "{:?}", f.messages());
    assert_eq!(
        unsafe { fmi3GetInt32(f.c, g.as_ptr(), 1, k.as_mut_ptr(), 3) },
        fmi3Error
    );
    let mut v = [0i32];
    assert_eq!(
        unsafe { fmi3GetInt32(f.c, vr.as_ptr(), 1, v.as_mut_ptr(), 1) },
        fmi3OK
    );
    assert_eq!(v[0], 4);
    let mut v2 = [0i32];
    assert_eq!(
        unsafe { fmi2GetInteger(f.c, order.members.as_ptr(), 1, v2.as_mut_ptr()) },
        fmi2OK
    );
    assert_eq!(v, v2);
    // time is Float64 only
    assert_eq!(
        unsafe { fmi3GetInt32(f.c, [0].as_ptr(), 1, v.as_mut_ptr(), 1) },
        fmi3Error
    );
    assert_eq!(f.get_f64(&[0], 1), (fmi3OK, vec![0.0]));
}

#[test]
fn types_without_variables_take_only_an_empty_list() {
    let m = TestModel::pendulum();
    let f = Fmu3::initialised(&m);
    let vr = [1u32];
    let none = std::ptr::null::<u32>();
    macro_rules! check {
        ($get:ident, $set:ident, $ty:ty, $zero:expr) => {{
            let mut v: [$ty; 1] = [$zero];
            unsafe {
                assert_eq!($get(f.c, none, 0, v.as_mut_ptr(), 0), fmi3OK);
                assert_eq!($set(f.c, none, 0, v.as_ptr(), 0), fmi3OK);
                assert_eq!($get(f.c, vr.as_ptr(), 1, v.as_mut_ptr(), 1), fmi3Error);
                assert!(f.last_message().contains("unknown value reference 1"));
                assert_eq!($set(f.c, vr.as_ptr(), 1, v.as_ptr(), 1), fmi3Error);
            }
        }};
    }
    check!(fmi3GetFloat32, fmi3SetFloat32, f32, 0.0);
    check!(fmi3GetInt8, fmi3SetInt8, i8, 0);
    check!(fmi3GetUInt8, fmi3SetUInt8, u8, 0);
    check!(fmi3GetInt16, fmi3SetInt16, i16, 0);
    check!(fmi3GetUInt16, fmi3SetUInt16, u16, 0);
    check!(fmi3GetUInt32, fmi3SetUInt32, u32, 0);
    check!(fmi3GetInt64, fmi3SetInt64, i64, 0);
    check!(fmi3GetUInt64, fmi3SetUInt64, u64, 0);
    check!(fmi3GetBoolean, fmi3SetBoolean, bool, false);
    check!(fmi3GetString, fmi3SetString, fmi3String, std::ptr::null());
    let mut sizes = [0usize];
    let mut bins: [fmi3Binary; 1] = [std::ptr::null()];
    let mut clocks = [false];
    unsafe {
        assert_eq!(
            fmi3GetBinary(f.c, none, 0, sizes.as_mut_ptr(), bins.as_mut_ptr(), 0),
            fmi3OK
        );
        assert_eq!(
            fmi3GetBinary(
                f.c,
                vr.as_ptr(),
                1,
                sizes.as_mut_ptr(),
                bins.as_mut_ptr(),
                1
            ),
            fmi3Error
        );
        assert_eq!(
            fmi3SetBinary(f.c, vr.as_ptr(), 1, sizes.as_ptr(), bins.as_ptr(), 1),
            fmi3Error
        );
        assert_eq!(
            fmi3SetBinary(f.c, none, 0, sizes.as_ptr(), bins.as_ptr(), 0),
            fmi3OK
        );
        assert_eq!(fmi3GetClock(f.c, none, 0, clocks.as_mut_ptr()), fmi3OK);
        assert_eq!(
            fmi3GetClock(f.c, vr.as_ptr(), 1, clocks.as_mut_ptr()),
            fmi3Error
        );
        assert_eq!(
            fmi3SetClock(f.c, vr.as_ptr(), 1, clocks.as_ptr()),
            fmi3Error
        );
    }
    // the instance keeps working
    assert_eq!(f.step(0.0, 0.01).0, fmi3OK);
}
