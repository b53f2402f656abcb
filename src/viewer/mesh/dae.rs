//! COLLADA (`.dae`) geometry: the triangles, polylists and polygons of every geometry that the
//! visual scene instantiates, placed by the node transforms (`matrix`, `translate`, `rotate`,
//! `scale`, nested nodes and `instance_node`), scaled by `<unit meter>` and turned so that the
//! file's `<up_axis>` becomes z (Y_UP: +90° about x, as Gazebo and RViz show such files), each
//! primitive coloured by the diffuse colour of its bound material. Textures, skins and
//! animations are ignored.

use std::collections::HashMap;

use nalgebra::{Matrix4, Rotation3, Unit, Vector3};

use super::dae_tree::{index, target, tree, Node};
use super::trimesh::{MeshPart, TriMesh};

/// One primitive of a geometry: positions (file units) and triangles, and its material symbol.
struct Primitive {
    positions: Vec<[f64; 3]>,
    indices: Vec<u32>,
    material: Option<String>,
}

/// The primitives of `<geometry>`'s `<mesh>`.
fn primitives(geometry: &Node, ids: &HashMap<&str, &Node>) -> Result<Vec<Primitive>, String> {
    let Some(mesh) = geometry.first("mesh") else {
        return Ok(Vec::new());
    };
    // the positions: a <source> directly, or through <vertices>
    let positions_of = |url: Option<&str>| -> Result<Vec<[f64; 3]>, String> {
        let mut node = target(ids, url).ok_or("an <input> names a source that does not exist")?;
        if node.name == "vertices" {
            let input = node
                .all("input")
                .find(|i| i.attr("semantic") == Some("POSITION"))
                .ok_or("<vertices> without a POSITION input")?;
            node = target(ids, input.attr("source")).ok_or("<vertices> names a missing source")?;
        }
        let floats: Vec<f64> = node
            .first("float_array")
            .ok_or("a position <source> without <float_array>")?
            .numbers()?;
        let stride = node
            .first("technique_common")
            .and_then(|t| t.first("accessor"))
            .and_then(|a| a.attr("stride"))
            .and_then(|s| s.parse::<usize>().ok())
            .unwrap_or(3)
            .max(3);
        Ok(floats
            .chunks_exact(stride)
            .map(|c| [c[0], c[1], c[2]])
            .collect())
    };
    let mut out = Vec::new();
    for prim in &mesh.children {
        if !matches!(
            prim.name.as_str(),
            "triangles" | "polylist" | "polygons" | "trifans"
        ) {
            continue;
        }
        let inputs: Vec<&Node> = prim.all("input").collect();
        let offset = |i: &Node| {
            i.attr("offset")
                .and_then(|o| o.parse::<usize>().ok())
                .unwrap_or(0)
        };
        let stride = inputs.iter().map(|i| offset(i) + 1).max().unwrap_or(1);
        let Some(vertex) = inputs
            .iter()
            .find(|i| matches!(i.attr("semantic"), Some("VERTEX" | "POSITION")))
        else {
            continue;
        };
        let positions = positions_of(vertex.attr("source"))?;
        let at = offset(vertex);
        // polygons as lists of position indices
        let mut polygons: Vec<Vec<usize>> = Vec::new();
        let take = |p: &[usize]| -> Vec<usize> {
            p.chunks(stride)
                .filter_map(|c| c.get(at).copied())
                .collect()
        };
        match prim.name.as_str() {
            "triangles" => {
                for p in prim.all("p") {
                    polygons.extend(take(&p.numbers()?).chunks_exact(3).map(<[usize]>::to_vec));
                }
            }
            "polylist" => {
                let counts: Vec<usize> = prim
                    .first("vcount")
                    .map(Node::numbers)
                    .transpose()?
                    .unwrap_or_default();
                let p: Vec<usize> = prim
                    .first("p")
                    .map(Node::numbers)
                    .transpose()?
                    .unwrap_or_default();
                let verts = take(&p);
                let mut k = 0;
                for c in counts {
                    let Some(poly) = verts.get(k..k + c) else {
                        return Err(
                            "<polylist>: <vcount> asks for more vertices than <p> has".into()
                        );
                    };
                    polygons.push(poly.to_vec());
                    k += c;
                }
            }
            _ => {
                for p in prim.all("p") {
                    polygons.push(take(&p.numbers()?));
                }
            }
        }
        // fans, then only the positions used
        let mut used: HashMap<usize, u32> = HashMap::new();
        let mut part = Primitive {
            positions: Vec::new(),
            indices: Vec::new(),
            material: prim.attr("material").map(String::from),
        };
        for poly in polygons.iter().filter(|p| p.len() >= 3) {
            for k in 1..poly.len() - 1 {
                for &v in &[poly[0], poly[k], poly[k + 1]] {
                    let p = *positions
                        .get(v)
                        .ok_or("a <p> index is past the positions")?;
                    let next =
                        u32::try_from(part.positions.len()).map_err(|_| "too many vertices")?;
                    let i = *used.entry(v).or_insert_with(|| {
                        part.positions.push(p);
                        next
                    });
                    part.indices.push(i);
                }
            }
        }
        out.push(part);
    }
    Ok(out)
}

/// The transform of a `<node>`'s own transform elements, in order.
fn node_transform(node: &Node) -> Result<Matrix4<f64>, String> {
    let mut m = Matrix4::identity();
    for c in &node.children {
        let x: Vec<f64> = match c.name.as_str() {
            "matrix" | "translate" | "rotate" | "scale" => c.numbers()?,
            _ => continue,
        };
        let need = match c.name.as_str() {
            "matrix" => 16,
            "rotate" => 4,
            _ => 3,
        };
        if x.len() < need {
            return Err(format!("<{}> needs {need} numbers", c.name));
        }
        m *= match c.name.as_str() {
            "matrix" => Matrix4::from_row_slice(&x[..16]),
            "translate" => Matrix4::new_translation(&Vector3::new(x[0], x[1], x[2])),
            "scale" => Matrix4::new_nonuniform_scaling(&Vector3::new(x[0], x[1], x[2])),
            _ => {
                let axis = Vector3::new(x[0], x[1], x[2]);
                if axis.norm() == 0.0 {
                    Matrix4::identity()
                } else {
                    Rotation3::from_axis_angle(&Unit::new_normalize(axis), x[3].to_radians())
                        .to_homogeneous()
                }
            }
        };
    }
    Ok(m)
}

/// Reads the triangles of the COLLADA document `text`.
pub(super) fn parse(text: &str) -> Result<TriMesh, String> {
    let root = tree(text)?;
    let mut ids = HashMap::new();
    index(&root, &mut ids);
    // the file's unit and up axis
    let asset = root.first("asset");
    let meter = asset
        .and_then(|a| a.first("unit"))
        .and_then(|u| u.attr("meter"))
        .and_then(|m| m.parse::<f64>().ok())
        .filter(|m| *m > 0.0 && m.is_finite())
        .unwrap_or(1.0);
    let up = asset
        .and_then(|a| a.first("up_axis"))
        .map_or("Y_UP", |u| u.text.trim());
    let turn = match up {
        "Z_UP" => Matrix4::identity(),
        // x up: x → z, z → −x
        "X_UP" => Rotation3::from_axis_angle(&Vector3::y_axis(), -std::f64::consts::FRAC_PI_2)
            .to_homogeneous(),
        _ => Rotation3::from_axis_angle(&Vector3::x_axis(), std::f64::consts::FRAC_PI_2)
            .to_homogeneous(),
    };
    let top = turn * Matrix4::new_scaling(meter);
    // the scene's geometry instances with their transforms and material bindings
    let mut instances: Vec<(Matrix4<f64>, &Node, HashMap<String, String>)> = Vec::new();
    let scene = root
        .first("scene")
        .and_then(|s| s.first("instance_visual_scene"))
        .and_then(|i| target(&ids, i.attr("url")))
        .or_else(|| {
            root.first("library_visual_scenes")
                .and_then(|l| l.first("visual_scene"))
        });
    match scene {
        Some(scene) => {
            for n in scene.all("node") {
                walk(n, top, &ids, &mut instances, 0)?;
            }
        }
        None => {
            for lib in root.all("library_geometries") {
                for g in lib.all("geometry") {
                    instances.push((top, g, HashMap::new()));
                }
            }
        }
    }
    let mut parts = Vec::new();
    for (m, geometry, bindings) in instances {
        for prim in primitives(geometry, &ids)? {
            let rgba = prim
                .material
                .as_ref()
                .and_then(|sym| bindings.get(sym))
                .and_then(|url| colour(&ids, url));
            parts.push(MeshPart {
                positions: prim
                    .positions
                    .iter()
                    .map(|p| {
                        let q = m.transform_point(&nalgebra::Point3::new(p[0], p[1], p[2]));
                        [q.x as f32, q.y as f32, q.z as f32]
                    })
                    .collect(),
                // a mirroring transform turns the triangles inside out: swap two corners
                indices: if m.fixed_view::<3, 3>(0, 0).determinant() < 0.0 {
                    prim.indices
                        .chunks_exact(3)
                        .flat_map(|t| [t[0], t[2], t[1]])
                        .collect()
                } else {
                    prim.indices
                },
                rgba,
            });
        }
    }
    Ok(TriMesh { parts })
}

/// Collects the geometry instances under `node` (transform `parent` above it).
fn walk<'a>(
    node: &'a Node,
    parent: Matrix4<f64>,
    ids: &HashMap<&'a str, &'a Node>,
    out: &mut Vec<(Matrix4<f64>, &'a Node, HashMap<String, String>)>,
    depth: usize,
) -> Result<(), String> {
    if depth > 64 {
        return Err("nodes nested more than 64 deep (a cycle of <instance_node>?)".into());
    }
    let m = parent * node_transform(node)?;
    for c in &node.children {
        match c.name.as_str() {
            "instance_geometry" => {
                if let Some(g) = target(ids, c.attr("url")) {
                    let bindings = c
                        .first("bind_material")
                        .and_then(|b| b.first("technique_common"))
                        .map(|t| {
                            t.all("instance_material")
                                .filter_map(|i| {
                                    Some((
                                        i.attr("symbol")?.to_string(),
                                        i.attr("target")?.to_string(),
                                    ))
                                })
                                .collect()
                        })
                        .unwrap_or_default();
                    out.push((m, g, bindings));
                }
            }
            "instance_node" => {
                if let Some(n) = target(ids, c.attr("url")) {
                    walk(n, m, ids, out, depth + 1)?;
                }
            }
            "node" => walk(c, m, ids, out, depth + 1)?,
            _ => {}
        }
    }
    Ok(())
}

/// The diffuse colour of the material at `url` (through its effect), if it is a colour.
fn colour(ids: &HashMap<&str, &Node>, url: &str) -> Option<[f32; 4]> {
    let material = target(ids, Some(url))?;
    let effect = target(ids, material.first("instance_effect")?.attr("url"))?;
    fn find<'a>(n: &'a Node, name: &str) -> Option<&'a Node> {
        if n.name == name {
            return Some(n);
        }
        n.children.iter().find_map(|c| find(c, name))
    }
    let c: Vec<f32> = find(effect, "diffuse")?.first("color")?.numbers().ok()?;
    (c.len() >= 3).then(|| [c[0], c[1], c[2], c.get(3).copied().unwrap_or(1.0)])
}

#[cfg(test)]
mod tests {
    use super::*;

    const QUAD: &str = r##"<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter="0.001"/><up_axis>Z_UP</up_axis></asset>
  <library_effects><effect id="red-fx"><profile_COMMON><technique sid="t"><phong>
    <diffuse><color>1 0 0 1</color></diffuse></phong></technique></profile_COMMON></effect></library_effects>
  <library_materials><material id="red"><instance_effect url="#red-fx"/></material></library_materials>
  <library_geometries><geometry id="quad"><mesh>
    <source id="pos"><float_array id="pos-a" count="12">0 0 0 1000 0 0 1000 1000 0 0 1000 0</float_array>
      <technique_common><accessor source="#pos-a" count="4" stride="3"/></technique_common></source>
    <vertices id="v"><input semantic="POSITION" source="#pos"/></vertices>
    <polylist material="m" count="1"><input semantic="VERTEX" source="#v" offset="0"/>
      <vcount>4</vcount><p>0 1 2 3</p></polylist>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s"><node><translate>0 0 500</translate>
    <instance_geometry url="#quad"><bind_material><technique_common>
      <instance_material symbol="m" target="#red"/></technique_common></bind_material></instance_geometry>
  </node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>"##;

    #[test]
    fn polylist_in_millimetres_with_a_node_transform_and_a_colour() {
        let m = parse(QUAD).unwrap();
        assert_eq!(m.parts.len(), 1);
        let p = &m.parts[0];
        assert_eq!(p.indices, [0, 1, 2, 0, 2, 3]);
        assert_eq!(p.positions[2], [1.0, 1.0, 0.5]);
        assert_eq!(p.rgba, Some([1.0, 0.0, 0.0, 1.0]));
    }

    #[test]
    fn y_up_turns_y_into_z() {
        let m = parse(&QUAD.replace("Z_UP", "Y_UP")).unwrap();
        let [x, y, z] = m.parts[0].positions[2];
        assert!((x - 1.0).abs() < 1e-6 && (y + 0.5).abs() < 1e-6 && (z - 1.0).abs() < 1e-6);
    }

    #[test]
    fn malformed_files_are_errors() {
        assert!(parse("<COLLADA><library_geometries>").is_err());
        assert!(parse("<robot/>").unwrap_err().contains("not a COLLADA"));
    }
}
