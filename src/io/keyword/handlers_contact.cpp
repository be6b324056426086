// Contacts: *CONTACT_AUTOMATIC_SURFACE_TO_SURFACE, _NODES_TO_SURFACE,
// _ONE_WAY_SURFACE_TO_SURFACE and _SINGLE_SURFACE, each with the _ID option. Card layouts follow
// the LS-DYNA keyword manual (as transcribed in ansys/pydyna, contact_automatic_*.py): an
// optional ID card (CID, HEADING), card 1 SSID MSID SSTYP MSTYP SBOXID MBOXID SPR MPR, card 2
// FS FD DC VC VDC PENCHK BT DT, card 3 SFS SFM SST MST SFST SFMT FSF VSF, optional card A
// SOFT SOFSCL LCIDAB MAXPAR SBOPT DEPTH BSORT FRCFRQ and optional card B PENMAX THKOPT SHLTHK
// SNLOG ISYM I2D3D SLDTHK SLDSTF. Fields that would change the physics in ways the solver does
// not model are errors when given a non-default value; search-tuning fields are accepted and
// not used (docs/keywords.md). The solver side is src/contact/contact.hpp.
#include <fmt/format.h>

#include <cmath>
#include <string>

#include "io/keyword/handlers.hpp"

namespace rf::io::handlers {

namespace {

const Layout kEightByTen = uniform_layout(8, 10);

double non_negative_real(const Card& card, std::size_t i, const char* name, double fallback) {
  const double v = card.real(i, name, fallback);
  if (!(v >= 0.0)) throw card.error(name, fmt::format("value {} must not be negative", v));
  return v;
}

void require_default(const Card& card, std::size_t i, const char* name, double fallback,
                     const char* why) {
  const double v = card.real(i, name, fallback);
  if (v != fallback) throw card.error(name, fmt::format("value {} is not supported: {}", v, why));
}

model::ContactKind kind_of(const std::string& base) {
  if (base == "*CONTACT_AUTOMATIC_NODES_TO_SURFACE") return model::ContactKind::NodesToSurface;
  if (base == "*CONTACT_AUTOMATIC_ONE_WAY_SURFACE_TO_SURFACE") {
    return model::ContactKind::OneWaySurfaceToSurface;
  }
  if (base == "*CONTACT_AUTOMATIC_SINGLE_SURFACE") return model::ContactKind::SingleSurface;
  return model::ContactKind::SurfaceToSurface;
}

}  // namespace

void contact_automatic(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  model::Contact contact;
  contact.number = static_cast<int>(context.model.contacts.size()) + 1;
  contact.id = contact.number;
  contact.kind = kind_of(block.base);
  int n = 1;
  if (block.has_option("ID") || block.has_option("TITLE")) {  // the same card
    const Card id_card = cursor.next(n++, Layout{10, 70}, "CID HEADING");
    const model::Id cid = id_card.id(0, "CID");
    if (cid < 0) throw id_card.error("CID", fmt::format("ID {} must not be negative", cid));
    if (cid != 0) contact.id = cid;
    contact.heading = std::string(id_card.text(1));
  }
  for (const auto& other : context.model.contacts) {
    if (other.id == contact.id) {
      throw block_error(
          block, 1, "CID",
          fmt::format("contact ID {} is already used by the contact at {}:{} ({}); "
                      "contacts without _ID are numbered by their position",
                      contact.id, other.where.file, other.where.line, other.where.keyword));
    }
  }

  const Card c1 = cursor.next(n++, kEightByTen, "SSID MSID SSTYP MSTYP SBOXID MBOXID SPR MPR");
  contact.where = c1.location();
  contact.ssid = c1.id(0, "SSID");
  contact.msid = c1.id(1, "MSID");
  contact.sstyp = static_cast<int>(c1.integer(2, "SSTYP", 0));
  contact.mstyp = static_cast<int>(c1.integer(3, "MSTYP", 0));
  const bool single = contact.kind == model::ContactKind::SingleSurface;
  const bool nodes_to_surface = contact.kind == model::ContactKind::NodesToSurface;
  if (single) {
    // SSID 0 with SSTYP 0 means every part for a single-surface contact.
    if (contact.ssid == 0 && contact.sstyp == 0) contact.sstyp = 5;
    if (contact.sstyp != 2 && contact.sstyp != 3 && contact.sstyp != 5) {
      throw c1.error("SSTYP", fmt::format("SSTYP {} is not supported for a single-surface "
                                          "contact: use 2 (part set), 3 (part) or 5 (all parts)",
                                          contact.sstyp));
    }
  } else {
    const bool slave_ok = contact.sstyp == 0 || contact.sstyp == 2 || contact.sstyp == 3 ||
                          contact.sstyp == 5 || (contact.sstyp == 4 && nodes_to_surface);
    if (!slave_ok) {
      throw c1.error("SSTYP",
                     fmt::format("SSTYP {} is not supported: 0 segment set, 2 part set, 3 part, "
                                 "5 all parts{}",
                                 contact.sstyp, nodes_to_surface ? ", 4 node set" : ""));
    }
    if (contact.mstyp != 0 && contact.mstyp != 2 && contact.mstyp != 3 && contact.mstyp != 5) {
      throw c1.error("MSTYP", fmt::format("MSTYP {} is not supported: 0 segment set, 2 part set, "
                                          "3 part, 5 all parts",
                                          contact.mstyp));
    }
    if (contact.sstyp != 5 && contact.ssid <= 0) {
      throw c1.error("SSID", fmt::format("SSID {} must name a set or part", contact.ssid));
    }
    if (contact.mstyp != 5 && contact.msid <= 0) {
      throw c1.error("MSID", fmt::format("MSID {} must name a set or part", contact.msid));
    }
  }
  if (c1.id(4, "SBOXID") != 0 || c1.id(5, "MBOXID") != 0) {
    throw c1.error(c1.id(4, "SBOXID") != 0 ? "SBOXID" : "MBOXID",
                   "contact boxes are not supported (leave SBOXID and MBOXID blank)");
  }

  const Card c2 = cursor.next(n++, kEightByTen, "FS FD DC VC VDC PENCHK BT DT");
  contact.fs = non_negative_real(c2, 0, "FS", 0.0);
  contact.fd = non_negative_real(c2, 1, "FD", 0.0);
  contact.dc = non_negative_real(c2, 2, "DC", 0.0);
  require_default(c2, 3, "VC", 0.0, "viscous friction limits are not modelled (leave VC 0)");
  contact.vdc = non_negative_real(c2, 4, "VDC", 0.0);
  if (contact.vdc > 100.0) {
    throw c2.error("VDC",
                   fmt::format("VDC {} is above 100 (percent of critical damping)", contact.vdc));
  }
  if (const auto penchk = c2.integer(5, "PENCHK", 0); penchk != 0) {
    context.warn(c2.location(), fmt::format("PENCHK {} ignored: nodes are released from contact "
                                            "when they are deeper than half the segment size",
                                            penchk));
  }
  contact.birth = non_negative_real(c2, 6, "BT", 0.0);
  contact.death = c2.real(7, "DT", 1e20);
  if (contact.death == 0.0) contact.death = 1e20;
  if (contact.death <= contact.birth) {
    throw c2.error("DT", fmt::format("death time {} must be later than the birth time BT {}",
                                     contact.death, contact.birth));
  }
  if (contact.fd == 0.0 && contact.fs > 0.0 && c2.blank(1)) contact.fd = contact.fs;

  const Card c3 = cursor.next(n++, kEightByTen, "SFS SFM SST MST SFST SFMT FSF VSF");
  contact.sfs = non_negative_real(c3, 0, "SFS", 1.0);
  contact.sfm = non_negative_real(c3, 1, "SFM", 1.0);
  if (contact.sfs == 0.0) contact.sfs = 1.0;  // LS-DYNA: 0 means the default
  if (contact.sfm == 0.0) contact.sfm = 1.0;
  contact.sst = non_negative_real(c3, 2, "SST", 0.0);
  contact.mst = non_negative_real(c3, 3, "MST", 0.0);
  // SFST/SFMT scale the shell thickness when SST/MST is 0 (0 means 1, as in LS-DYNA).
  contact.sfst = non_negative_real(c3, 4, "SFST", 1.0);
  contact.sfmt = non_negative_real(c3, 5, "SFMT", 1.0);
  if (contact.sfst == 0.0) contact.sfst = 1.0;
  if (contact.sfmt == 0.0) contact.sfmt = 1.0;
  contact.fsf = non_negative_real(c3, 6, "FSF", 1.0);
  if (contact.fsf == 0.0) contact.fsf = 1.0;

  cursor.skip_blank_lines();
  if (!cursor.at_end()) {
    const Card a =
        cursor.next(n++, kEightByTen, "SOFT SOFSCL LCIDAB MAXPAR SBOPT DEPTH BSORT FRCFRQ");
    contact.soft = static_cast<int>(a.integer(0, "SOFT", 0));
    if (contact.soft != 0 && contact.soft != 1) {
      throw a.error("SOFT", fmt::format("SOFT {} is not supported: 0 (stiffness from the "
                                        "segment's bulk modulus) or 1 (from mass and time step)",
                                        contact.soft));
    }
    contact.sofscl = non_negative_real(a, 1, "SOFSCL", 0.1);
    if (contact.sofscl == 0.0) contact.sofscl = 0.1;
    if (a.id(2, "LCIDAB") != 0) {
      throw a.error("LCIDAB", "airbag contact curves are not supported (leave LCIDAB blank)");
    }
    // MAXPAR, SBOPT, DEPTH, BSORT, FRCFRQ tune the search of SOFT = 2 or the bucket-sort
    // interval: the solver's search is exact (rebuilt as motion requires), so they are unused.
  }
  cursor.skip_blank_lines();
  if (!cursor.at_end()) {
    const Card b =
        cursor.next(n++, kEightByTen, "PENMAX THKOPT SHLTHK SNLOG ISYM I2D3D SLDTHK SLDSTF");
    // PENMAX, THKOPT, SHLTHK, SNLOG, ISYM and I2D3D concern shells, symmetry planes and
    // penetration release; only the solid thickness and stiffness overrides would change this
    // model's physics.
    require_default(b, 6, "SLDTHK", 0.0, "solid contact thickness is not modelled");
    require_default(b, 7, "SLDSTF", 0.0, "solid contact stiffness override is not modelled");
  }
  context.model.contacts.push_back(std::move(contact));
  warn_unread_lines(block, cursor, context);
}

// *CONTROL_CONTACT (LS-DYNA Keyword User's Manual, *CONTROL_CONTACT; six optional cards). Each
// field is one of: used (SLSFAC, PENOPT 0-3: which side's stiffness a pair takes), what our
// contacts already do (ENMASS 0: nodes of eroded elements are removed), no effect on them
// (checks, search tuning, output, options of contact types we do not read), or refused when set,
// because it would change the physics (default friction and damping for every contact,
// initial-penetration handling, rigid-wall penalties, spot-weld options, thermal contact, symmetry
// planes, edge treatment). docs/keywords.md lists each.
void control_contact(const Block& block, ReaderContext& context) {
  CardCursor cursor(block, context.parameters);
  model::ContactControl& control = context.model.contact_control;
  // Refused unless blank or equal to the default `fallback`.
  auto refuse = [](const Card& card, std::size_t i, const char* name, double fallback,
                   const char* what) {
    const double v = card.real(i, name, fallback);
    if (v != fallback)
      throw card.error(name, fmt::format("value {} is not supported: {} (leave it blank or {})", v,
                                         what, fallback));
  };
  const Card c1 =
      cursor.next(1, kEightByTen, "SLSFAC RWPNAL ISLCHK SHLTHK PENOPT THKCHG ORIEN ENMASS");
  control.where = c1.location();
  const double slsfac = c1.real(0, "SLSFAC", 0.0);
  if (slsfac < 0.0 || !std::isfinite(slsfac))
    throw c1.error("SLSFAC", fmt::format("penalty scale {} must be positive (blank: 0.1)", slsfac));
  control.slsfac = slsfac > 0.0 ? slsfac : 0.1;
  refuse(c1, 1, "RWPNAL", 0.0,
         "rigid walls act by the constraint method here (penalty walls are not implemented)");
  const double penopt = c1.real(4, "PENOPT", 0.0);
  if (penopt != 0.0 && penopt != 1.0 && penopt != 2.0 && penopt != 3.0)
    throw c1.error("PENOPT", fmt::format("PENOPT {} is not supported (1 or blank: the smaller of "
                                         "the master segment's and the slave node's stiffness, 2: "
                                         "the master segment's, 3: the slave node's; the area- or "
                                         "mass-weighted 4 and 5 are not implemented)",
                                         penopt));
  control.penopt = penopt == 0.0 ? 1 : static_cast<int>(penopt);
  refuse(c1, 7, "ENMASS", 0.0,
         "nodes left without elements by erosion are removed from the model and from contact "
         "(ENMASS 0)");
  // THKCHG (contact thickness following the shells' thickness update): stored; with a thickness
  // update (*CONTROL_SHELL ISTUPD != 0) a nonzero value is refused when the shells are built
  // (solver/build_structural.cpp), as the contacts keep the initial offset (THKCHG 0, LS-DYNA's
  // default). ISLCHK (a check), SHLTHK (automatic contacts always offset by the shell
  // thickness), ORIEN (orientation of non-automatic contacts): no effect.
  const double thkchg = c1.real(5, "THKCHG", 0.0);
  if (thkchg != 0.0 && thkchg != 1.0 && thkchg != 2.0)
    throw c1.error("THKCHG", fmt::format("value {} is not 0, 1 or 2", thkchg));
  control.thkchg = static_cast<int>(thkchg);
  if (const auto c2 = cursor.next_optional(2, kEightByTen)) {
    refuse(*c2, 0, "USRSTR", 0.0, "user contact subroutines are not supported");
    refuse(*c2, 1, "USRFRC", 0.0, "user friction subroutines are not supported");
    refuse(*c2, 5, "SSTHK", 0.0,
           "single-surface contacts take the thickness of *CONTACT card 3 (SST, SFST)");
    // NSBCS, INTERM, XPENE (search and penetration checks of other contact types), ECDT (the
    // contacts never enter the time step), TIEDPRJ (tied contacts): no effect.
  }
  if (const auto c3 = cursor.next_optional(3, kEightByTen)) {
    static const char* const kNames[] = {"SFRIC", "DFRIC", "EDC", "VFC", "TH", "TH_SF", "PEN_SF"};
    for (std::size_t k = 0; k < 7; ++k)
      refuse(*c3, k, kNames[k], 0.0,
             k < 4 ? "default friction and damping for every contact (give FS, FD, DC, VDC on "
                     "each *CONTACT instead)"
                   : "thermal contact is not implemented");
  }
  if (const auto c4 = cursor.next_optional(4, kEightByTen)) {
    refuse(*c4, 0, "IGNORE", 0.0,
           "initial penetrations are not treated specially (they are pushed out by the penalty)");
    refuse(*c4, 4, "SPOTSTP", 0.0, "spot weld checks are not implemented");
    refuse(*c4, 5, "SPOTDEL", 0.0,
           "spot welds are not deleted with their elements (*CONSTRAINED_SPOTWELD)");
    refuse(*c4, 6, "SPOTHIN", 0.0, "spot weld thinning is not implemented");
    // FRCENG, SKIPRWG, OUTSEG: output options.
  }
  if (const auto c5 = cursor.next_optional(5, kEightByTen)) {
    refuse(*c5, 0, "ISYM", 0.0, "symmetry planes in contact are not implemented");
    refuse(*c5, 1, "NSEROD", 0.0, "eroding node-to-surface options are not implemented");
    refuse(*c5, 2, "RWGAPS", 1.0, "rigid wall gaps of shells are not implemented");
    refuse(*c5, 3, "RWGDTH", 0.0, "rigid wall gaps of shells are not implemented");
    const double rwksf = c5->real(4, "RWKSF", 1.0);
    if (rwksf != 0.0 && rwksf != 1.0)
      throw c5->error("RWKSF", fmt::format("value {} is not supported: rigid walls act by the "
                                           "constraint method (leave it blank or 1)",
                                           rwksf));
    refuse(*c5, 5, "ICOV", 0.0, "invariant node numbering is not implemented");
    refuse(*c5, 6, "SWRADF", 0.0, "spot weld radius scaling is not implemented");
    refuse(*c5, 7, "ITHOFF", 0.0, "thermal contact is not implemented");
  }
  if (const auto c6 = cursor.next_optional(6, kEightByTen)) {
    static const char* const kNames[] = {"SHLEDG", "PSTIFF", "ITHCNT", "TDCNOF",
                                         "FTALL",  "",       "SHLTRW", "IGACTC"};
    for (std::size_t k = 0; k < 8; ++k) {
      if (k == 5) continue;
      refuse(*c6, k, kNames[k], 0.0, "this contact option is not implemented");
    }
  }
  warn_unread_lines(block, cursor, context);
}

void check_contacts(const model::Model& model) {
  auto check_side = [&](const model::Contact& c, model::Id id, int type, const char* field) {
    switch (type) {
      case 0:
        if (!model.segment_sets.count(id)) {
          throw located_error(c.where, field,
                              fmt::format("segment set {} is not defined (*SET_SEGMENT)", id));
        }
        break;
      case 2:
        if (!model.part_sets.count(id)) {
          throw located_error(c.where, field,
                              fmt::format("part set {} is not defined (*SET_PART)", id));
        }
        break;
      case 3:
        if (!model.parts.count(id)) {
          throw located_error(c.where, field, fmt::format("part {} is not defined", id));
        }
        break;
      case 4:
        if (!model.node_sets.count(id)) {
          throw located_error(c.where, field,
                              fmt::format("node set {} is not defined (*SET_NODE)", id));
        }
        break;
      default:
        break;
    }
  };
  for (const auto& c : model.contacts) {
    check_side(c, c.ssid, c.sstyp, "SSID");
    if (c.kind != model::ContactKind::SingleSurface) check_side(c, c.msid, c.mstyp, "MSID");
  }
}

}  // namespace rf::io::handlers
